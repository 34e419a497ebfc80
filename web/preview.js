// web/preview.js — the first frame of a large scene: the server's coarse copy (preview.bin,
// cli/view/view_preview.h: vertex clustering, each preview vertex a scene vertex with its own
// transfer) drawn with the same relighting material while the full payloads are on the way.
// The full frame replaces it as soon as they have arrived (viewer.js). The preview stays: while
// the user turns the light, orbits or slides, the page draws it (a frame in a tenth of the
// time) and redraws in full once the input has rested for kRefineMs.
import * as THREE from 'three';
import { addDefaultAttributes, createRelightMaterial, halfTexture } from './prt-relight.js';

export const kRefineMs = 250;

// Whether the page draws the preview first: the manifest has one, the display is the file's
// transfer (the preview carries no AO, bent normals or emitter light) and preview=0 is absent.
export function wantsPreview(manifest, params) {
  return !!manifest.preview && !manifest.emitters && (params.get('mode') ?? 'transfer') === 'transfer' &&
    params.get('preview') !== '0';
}

// The preview as a mesh with its own relighting material (the same shader as the full mesh's:
// three.js compiles it once).
export function previewMesh(manifest, buffer) {
  const p = manifest.preview, s = p.sections;
  const view = (info, Type) => new Type(buffer, info.offset, info.count);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(view(s.positions, Float32Array), 3));
  geometry.setAttribute('normal', new THREE.BufferAttribute(view(s.normals, Float32Array), 3));
  geometry.setAttribute('albedo', new THREE.BufferAttribute(view(s.albedo, Float32Array), 3));
  geometry.setIndex(new THREE.BufferAttribute(view(s.indices, Uint32Array), 1));
  addDefaultAttributes(geometry);
  geometry.computeBoundingSphere();
  const t = p.transfer;
  const material = createRelightMaterial({
    order: manifest.order,
    channels: manifest.channels,
    albedoFolded: manifest.albedo_folded,
    transfer: { texture: halfTexture(view(s.transfer, Uint16Array), t.width, t.height), width: t.width, texelsPerVertex: t.texels_per_vertex },
  });
  const mesh = new THREE.Mesh(geometry, material);
  mesh.frustumCulled = false;
  return mesh;
}

