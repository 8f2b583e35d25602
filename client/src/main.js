// Penumbra's lightmap client: loads a bake's scene.gltf (MOZ_lightmap atlases on TEXCOORD_1)
// and lightmaps.json from /bake/, shows it from the glTF's camera with orbit controls, shaded
// as preview.png (preview_shading.js). The body's data-state says loading, loaded or error;
// an error is a message in #status, never a blank canvas.
import * as THREE from 'three';
import {GLTFLoader} from 'three/addons/loaders/GLTFLoader.js';
import {OrbitControls} from 'three/addons/controls/OrbitControls.js';

import {MozLightmapPlugin} from './moz_lightmap.js';
import {PreviewRenderer, previewMaterial} from './preview_shading.js';

const statusLine = document.getElementById('status');
const canvas = document.getElementById('view');

function setState(state, message) {
    document.body.dataset.state = state;
    statusLine.textContent = message;
    statusLine.className = state === 'error' ? 'error' : '';
}

function createRenderer() {
    if (!canvas.getContext('webgl2', {antialias: false, preserveDrawingBuffer: true}))
        throw new Error('WebGL 2 is not available in this browser: the lightmaps cannot be shown');
    return new THREE.WebGLRenderer({canvas, antialias: false, preserveDrawingBuffer: true});
}

async function fetchJson(url) {
    const response = await fetch(url);
    if (!response.ok)
        throw new Error(`cannot load ${url.pathname}: ${response.status} ${response.statusText}`);
    return response.json();
}

async function loadGltf(url) {
    const loader = new GLTFLoader().register((parser) => new MozLightmapPlugin(parser));
    try {
        return await loader.loadAsync(url.href);
    } catch (error) {
        throw new Error(`cannot load ${url.pathname}: ${error.message ?? error}`);
    }
}

// The glTF's first camera, moved to the top level with its world pose, and the point on its
// view axis nearest the scene's centre (the orbit's pivot).
function sceneCamera(gltf) {
    gltf.scene.updateMatrixWorld(true);
    const camera = gltf.cameras[0];
    if (!camera) throw new Error('the glTF has no camera (the scene file needs a "camera")');
    const world = camera.matrixWorld.clone();
    camera.removeFromParent();
    world.decompose(camera.position, camera.quaternion, camera.scale);
    camera.up.set(0, 1, 0).applyQuaternion(camera.quaternion);
    const forward = new THREE.Vector3(0, 0, -1).applyQuaternion(camera.quaternion);
    const centre = new THREE.Box3().setFromObject(gltf.scene).getCenter(new THREE.Vector3());
    const depth = centre.clone().sub(camera.position).dot(forward);
    const target = camera.position.clone().addScaledVector(forward, depth > 0 ? depth : 1);
    return {camera, target};
}

// Every mesh's material replaced by the preview's shading of it.
function usePreviewMaterials(root, exposure) {
    const made = new Map();
    root.traverse((object) => {
        if (!object.isMesh) return;
        if (!made.has(object.material))
            made.set(object.material, previewMaterial(object.material, exposure));
        object.material = made.get(object.material);
    });
}

async function main() {
    const renderer = createRenderer();
    const query = new URLSearchParams(location.search);
    const gltfUrl = new URL(`/bake/${query.get('gltf') ?? 'scene.gltf'}`, location.href);
    const manifest = await fetchJson(new URL('lightmaps.json', gltfUrl));
    const preview = manifest.preview;
    if (!preview) throw new Error('lightmaps.json has no preview (the bake had no camera)');
    const gltf = await loadGltf(gltfUrl);
    const {camera, target} = sceneCamera(gltf);
    usePreviewMaterials(gltf.scene, preview.png_exposure);

    const aspect = camera.aspect;
    const size = () => {
        const width = Math.min(innerWidth, Math.round(innerHeight * aspect));
        return [width, Math.round(width / aspect)];
    };
    const view = new PreviewRenderer(renderer, {
        samplesPerPixel: preview.samples_per_pixel ?? 16,
        background: preview.background ?? [0, 0, 0],
        exposure: preview.png_exposure,
    });
    const draw = () => view.render(gltf.scene, camera);
    const resize = () => {
        const [width, height] = size();
        renderer.setPixelRatio(devicePixelRatio);
        renderer.setSize(width, height);
        view.setSize(canvas.width, canvas.height);
        draw();
    };
    const controls = new OrbitControls(camera, canvas);
    controls.target.copy(target);
    controls.update();
    controls.addEventListener('change', draw);
    addEventListener('resize', resize);
    resize();
    setState('loaded', `${gltfUrl.pathname}: ${view.strata}×${view.strata} samples per pixel`);
}

main().catch((error) => {
    console.error(error);
    setState('error', `Penumbra: ${error.message ?? error}`);
});
