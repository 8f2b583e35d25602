// The shading of penumbra's preview.png (app/src/lightmap_preview.cpp), on the GPU:
//   1. each surface seen from its front shows the radiance L = ρ E / π + L_e, with E the
//      irradiance from a bilinear lookup of its lightmap at TEXCOORD_1 and L_e its emitted
//      radiance; the back of a surface is black, the background the scene's background;
//   2. the picture is rendered at `strata` × `strata` samples per pixel into a half-float target, of
//      exposure × L (exposure: lightmaps.json's preview.png_exposure);
//   3. each pixel is the mean of its samples (a box filter, as the preview's stratified
//      samples), clamped to [0, 1] and sRGB-encoded (core/src/image.cpp's encode_srgb).
// Units: a MOZ_lightmap texel decodes (sRGB → linear, by the GPU before filtering) to
// 179 lm/W × E / intensity, so E = decoded × intensity / 179 in W/m²; the material's emissive
// colour × emissive strength is 179 lm/W × L_e in cd/m².
import * as THREE from 'three';

export const LUMINOUS_EFFICACY = 179; // lm/W, as core/rgb.h

const surfaceVertexShader = `
precision highp float;
uniform mat4 modelViewMatrix;
uniform mat4 projectionMatrix;
in vec3 position;
in vec2 uv1;
out vec2 lightmapUv;
void main() {
    lightmapUv = uv1;
    gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}`;

const surfaceFragmentShader = `
precision highp float;
uniform sampler2D lightmap;
uniform float irradiancePerUnit; // W/m² per decoded lightmap unit
uniform vec3 albedo;             // ρ
uniform vec3 emitted;            // L_e, W/(sr m²)
uniform float exposure;
in vec2 lightmapUv;
out vec4 radiance;
void main() {
    if (!gl_FrontFacing) {
        radiance = vec4(0.0, 0.0, 0.0, 1.0);
        return;
    }
    vec3 irradiance = texture(lightmap, lightmapUv).rgb * irradiancePerUnit;
    radiance = vec4(exposure * (albedo * irradiance / 3.141592653589793 + emitted), 1.0);
}`;

const resolveVertexShader = `
precision highp float;
in vec3 position;
void main() { gl_Position = vec4(position.xy, 0.0, 1.0); }`;

const resolveFragmentShader = `
precision highp float;
uniform sampler2D samples;
uniform int strata;
out vec4 colour;
float encodeSrgb(float linear) {
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * pow(linear, 1.0 / 2.4) - 0.055;
}
void main() {
    ivec2 first = ivec2(gl_FragCoord.xy) * strata;
    vec3 sum = vec3(0.0);
    for (int j = 0; j < strata; ++j)
        for (int i = 0; i < strata; ++i)
            sum += texelFetch(samples, first + ivec2(i, j), 0).rgb;
    vec3 v = clamp(sum / float(strata * strata), 0.0, 1.0);
    colour = vec4(encodeSrgb(v.r), encodeSrgb(v.g), encodeSrgb(v.b), 1.0);
}`;

// The preview's material for one glTF material (as GLTFLoader made it, with MozLightmapPlugin).
export function previewMaterial(source, exposure) {
    if (!source.lightMap)
        throw new Error(`material "${source.name}" has no MOZ_lightmap: not a penumbra bake?`);
    const emitted = source.emissive.clone().multiplyScalar(
        (source.emissiveIntensity ?? 1) / LUMINOUS_EFFICACY);
    return new THREE.RawShaderMaterial({
        name: source.name,
        glslVersion: THREE.GLSL3,
        vertexShader: surfaceVertexShader,
        fragmentShader: surfaceFragmentShader,
        side: THREE.DoubleSide,
        uniforms: {
            lightmap: {value: source.lightMap},
            irradiancePerUnit: {value: source.lightMapIntensity / LUMINOUS_EFFICACY},
            albedo: {value: source.color.clone()},
            emitted: {value: emitted},
            exposure: {value: exposure},
        },
    });
}

// Supersampled targets larger than this many samples take fewer strata (a full-screen window).
const MAX_TARGET_SAMPLES = 8 * 1024 * 1024; // 64 MB of half floats

// Renders a scene as the preview does: supersampled into a float target, resolved to the canvas.
// `samplesPerPixel` is the preview camera's: strata = its square root, rounded up.
export class PreviewRenderer {
    constructor(renderer, {samplesPerPixel, background, exposure}) {
        this.renderer = renderer;
        this.preferredStrata = Math.ceil(Math.sqrt(samplesPerPixel));
        this.strata = this.preferredStrata;
        this.target = new THREE.WebGLRenderTarget(1, 1, {
            // Half floats: 11 significant bits, far below an 8-bit step after the mean; values
            // past 65 504 become infinite and clamp to white, as the preview clamps them.
            type: THREE.HalfFloatType,
            minFilter: THREE.NearestFilter,
            magFilter: THREE.NearestFilter,
            depthBuffer: true,
        });
        const [r, g, b] = background;
        this.clear = new THREE.Color().setRGB(exposure * r, exposure * g, exposure * b,
                                              THREE.LinearSRGBColorSpace);
        this.resolve = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), new THREE.RawShaderMaterial({
            glslVersion: THREE.GLSL3,
            vertexShader: resolveVertexShader,
            fragmentShader: resolveFragmentShader,
            uniforms: {samples: {value: this.target.texture}, strata: {value: this.strata}},
            depthTest: false,
            depthWrite: false,
        }));
        this.resolve.frustumCulled = false;
        this.resolveCamera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
    }

    // The drawing buffer's size in pixels; the target holds strata² samples per pixel, fewer
    // when it would be too large.
    setSize(width, height) {
        const maxSize = this.renderer.capabilities.maxTextureSize;
        let strata = this.preferredStrata;
        while (strata > 1 && (width * height * strata * strata > MAX_TARGET_SAMPLES ||
                              Math.max(width, height) * strata > maxSize))
            --strata;
        this.strata = strata;
        this.resolve.material.uniforms.strata.value = strata;
        this.target.setSize(width * strata, height * strata);
    }

    render(scene, camera) {
        const r = this.renderer;
        r.setRenderTarget(this.target);
        r.setClearColor(this.clear, 1);
        r.clear();
        r.render(scene, camera);
        r.setRenderTarget(null);
        r.render(this.resolve, this.resolveCamera);
    }
}
