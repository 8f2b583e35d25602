// MOZ_lightmap (Khronos vendor registry) for three.js's GLTFLoader, which does not read it:
// the material's lightmap texture (sRGB, on the texCoord it names) becomes the material's
// lightMap, and the extension's intensity its lightMapIntensity. A texture that fails to load
// is an error naming its image, not a material without light.
import { SRGBColorSpace } from 'three';

export class MozLightmapPlugin {
    constructor(parser) {
        this.parser = parser;
        this.name = 'MOZ_lightmap';
    }

    async extendMaterialParams(materialIndex, materialParams) {
        const material = this.parser.json.materials[materialIndex];
        const extension = material.extensions && material.extensions[this.name];
        if (!extension) return;
        // GLTFLoader turns a texture that fails to load into none (with a console message).
        await this.parser.assignTexture(materialParams, 'lightMap', extension.texture,
                                        SRGBColorSpace);
        if (!materialParams.lightMap)
            throw new Error(`cannot load the lightmap atlas ${this.imageUri(extension.texture)}`);
        materialParams.lightMapIntensity = extension.intensity ?? 1;
    }

    imageUri(textureInfo) {
        const json = this.parser.json;
        const texture = json.textures[textureInfo.index];
        const image = texture && json.images[texture.source];
        return image && image.uri ? image.uri : `of texture ${textureInfo.index}`;
    }
}
