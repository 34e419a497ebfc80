// web/passes/ao_passes.js — the screen-space AO display modes of the viewer (docs/VIEWER.md,
// "Adding a pass"; docs/SSAO.md): classic SSAO (ssao_classic.js) and GTAO (gtao.js), shown as
// grey without tone mapping beside the built-in 'baked AO' mode (the file's per-vertex AO, or
// obscurance when the bake had --ao-distance). Their parameters come from the page's URL:
// radius=R (scene units; default 1/10 of the mesh's bounding-box diagonal), samples=N (classic,
// 1..64, default 32), slices=N and steps=N (GTAO, default 4 and 8), blur=0|1 (default 1).
// web/ssao.html is the same passes on a page of their own (its read-back API is what
// `prt report --ssao` measures).
import * as THREE from 'three';
import { GBuffer, FullscreenPass, floatTarget, bindFrame, blurMaterial } from './ao_common.js';
import { classicSsaoMaterial } from './ssao_classic.js';
import { gtaoMaterial } from './gtao.js';

function settingsFromUrl(geometry) {
  const params = new URLSearchParams(location.search);
  const number = (name, fallback) => (params.has(name) ? Number(params.get(name)) : fallback);
  geometry.computeBoundingBox();
  const diagonal = geometry.boundingBox.getSize(new THREE.Vector3()).length();
  return {
    radius: number('radius', diagonal / 10),
    samples: number('samples', 32),
    slices: number('slices', 4),
    steps: number('steps', 8),
    blur: number('blur', 1) !== 0,
  };
}

const showMaterial = () =>
  new THREE.ShaderMaterial({
    glslVersion: THREE.GLSL3,
    vertexShader: 'out vec2 vUv; void main() { vUv = uv; gl_Position = vec4(position.xy, 0.0, 1.0); }',
    fragmentShader: `precision highp float; uniform sampler2D tAo; in vec2 vUv; out highp vec4 o;
      void main() { vec4 a = texture(tAo, vUv); o = vec4(a.w > 0.5 ? vec3(a.r) : vec3(0.1, 0.1, 0.12), 1.0); }`,
    uniforms: { tAo: { value: null } },
    depthTest: false,
    depthWrite: false,
  });

function makeAoPass(name, label, makeMaterial) {
  let s = null;  // settings, targets and passes, made by init and resized by render
  const size = new THREE.Vector2();
  const allocate = (width, height) => {
    s.width = width;
    s.height = height;
    s.gbuffer = new GBuffer(width, height);
    s.raw = floatTarget(width, height);
    s.out = floatTarget(width, height);
  };
  return {
    name,
    label,
    init(context) {
      s = { settings: settingsFromUrl(context.geometry) };
      s.pass = new FullscreenPass(makeMaterial(s.settings));
      s.blur = new FullscreenPass(blurMaterial());
      s.show = new FullscreenPass(showMaterial());
      context.renderer.getDrawingBufferSize(size);
      allocate(size.x, size.y);
    },
    render(context) {
      const { renderer, scene, camera } = context;
      renderer.getDrawingBufferSize(size);
      if (size.x !== s.width || size.y !== s.height) allocate(size.x, size.y);
      camera.updateMatrixWorld();
      s.gbuffer.render(renderer, scene, camera);
      bindFrame(s.pass.material, s.gbuffer, camera, s.settings.radius);
      s.pass.render(renderer, s.settings.blur ? s.raw : s.out);
      if (s.settings.blur) {
        const u = s.blur.material.uniforms;
        u.tAo.value = s.raw.texture;
        u.tPosition.value = s.gbuffer.position.texture;
        u.uTexel.value.set(1 / s.width, 1 / s.height);
        s.blur.render(renderer, s.out);
      }
      s.show.material.uniforms.tAo.value = s.out.texture;
      s.show.render(renderer, null);
    },
  };
}

export const ssaoPass = makeAoPass('ssao', 'SSAO (classic, screen space)', (o) =>
  classicSsaoMaterial(o.samples),
);
export const gtaoPass = makeAoPass('gtao', 'GTAO (screen space)', (o) =>
  gtaoMaterial(o.slices, o.steps),
);
