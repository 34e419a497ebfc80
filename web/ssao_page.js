// web/ssao_page.js — the ambient-occlusion page of `prt view` (/ssao.html): the file's per-vertex
// AO (baked AO, or obscurance when the bake had --ao-distance) beside two screen-space
// estimates, classic SSAO (passes/ssao_classic.js) and GTAO (passes/gtao.js), shown as grey
// without tone mapping (the value itself: 1 white, 0 black).
//
// URL parameters (all optional):
//   mode=baked|ssao|gtao   what is shown (default baked)
//   radius=R               the screen-space passes' radius in scene units (default: 1/10 of the
//                          scene's bounding-box diagonal)
//   samples=N              classic SSAO kernel size, 1..64 (default 32)
//   slices=N, steps=N      GTAO slices (default 4) and horizon steps per side (default 8)
//   blur=0|1               the 4×4 blur of the noise tile (default 1)
//   w=W, h=H               canvas size in pixels (default: the window)
//   eye=x,y,z target=x,y,z up=x,y,z fov=DEGREES   the camera (default: the manifest's, which is
//                          `prt relight`'s automatic camera)
// window.prtAO (for the headless capture of `prt report --ssao`): ready (a promise), the
// parameters in use, and read(which) → Float32Array of w·h·4 floats, rows bottom to top, for
// which = 'position' | 'normal' (the G-buffer, ao_common.js) | 'ssao' | 'gtao' | 'baked'
// (AO in the red channel, alpha 1 where a surface covers the pixel); readBase64(which) the same
// bytes as base64 text.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GBuffer, FullscreenPass, floatTarget, bindFrame, blurMaterial } from './passes/ao_common.js';
import { classicSsaoMaterial } from './passes/ssao_classic.js';
import { gtaoMaterial } from './passes/gtao.js';

const params = new URLSearchParams(location.search);
const number = (name, fallback) => (params.has(name) ? Number(params.get(name)) : fallback);
const vector = (name, fallback) =>
  params.has(name) ? new THREE.Vector3(...params.get(name).split(',').map(Number)) : fallback;

async function loadScene() {
  const manifest = await (await fetch('./api/manifest.json')).json();
  const bytes = await (await fetch(manifest.mesh.url.replace(/^\//, './'))).arrayBuffer();
  const section = (name, Type) => {
    const s = manifest.mesh.sections[name];
    return s ? new Type(bytes, s.offset, s.count) : null;
  };
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(section('positions', Float32Array), 3));
  geometry.setAttribute('normal', new THREE.BufferAttribute(section('normals', Float32Array), 3));
  const vertices = manifest.vertex_count;
  const ao = section('ao', Float32Array) ?? new Float32Array(vertices).fill(1);
  geometry.setAttribute('ao', new THREE.BufferAttribute(ao, 1));
  geometry.setIndex(new THREE.BufferAttribute(section('indices', Uint32Array), 1));
  geometry.computeBoundingBox();
  return { manifest, geometry, hasAo: manifest.mesh.sections.ao !== undefined };
}

function makeCamera(manifest, box, width, height) {
  const c = manifest.camera;
  const eye = vector('eye', new THREE.Vector3(...c.eye));
  const target = vector('target', new THREE.Vector3(...c.target));
  const camera = new THREE.PerspectiveCamera(number('fov', c.yfov_degrees), width / height);
  camera.up.copy(vector('up', new THREE.Vector3(...c.up)));
  camera.position.copy(eye);
  camera.lookAt(target);
  const size = box.getSize(new THREE.Vector3()).length();
  const far = eye.distanceTo(box.getCenter(new THREE.Vector3())) + size;
  camera.near = Math.max(far * 1e-4, 1e-6);
  camera.far = far * 2;
  camera.updateProjectionMatrix();
  camera.updateMatrixWorld();
  return { camera, target, diagonal: size };
}

async function main() {
  const { manifest, geometry, hasAo } = await loadScene();
  const width = number('w', window.innerWidth), height = number('h', window.innerHeight);
  const renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(width, height);
  renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
  renderer.toneMapping = THREE.NoToneMapping;
  document.body.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.add(new THREE.Mesh(geometry, new THREE.MeshBasicMaterial()));
  const { camera, target, diagonal } = makeCamera(manifest, geometry.boundingBox, width, height);

  const settings = {
    mode: params.get('mode') ?? 'baked',
    radius: number('radius', diagonal / 10),
    samples: number('samples', 32),
    slices: number('slices', 4),
    steps: number('steps', 8),
    blur: number('blur', 1) !== 0,
    width,
    height,
  };
  const gbuffer = new GBuffer(width, height);
  const raw = floatTarget(width, height), out = floatTarget(width, height);
  const passes = {
    ssao: new FullscreenPass(classicSsaoMaterial(settings.samples)),
    gtao: new FullscreenPass(gtaoMaterial(settings.slices, settings.steps)),
  };
  const blur = new FullscreenPass(blurMaterial());
  const baked = new FullscreenPass(
    new THREE.ShaderMaterial({
      glslVersion: THREE.GLSL3,
      vertexShader: 'out vec2 vUv; void main() { vUv = uv; gl_Position = vec4(position.xy, 0.0, 1.0); }',
      fragmentShader: `precision highp float; uniform sampler2D tNormal; in vec2 vUv; out highp vec4 o;
        void main() { vec4 n = texture(tNormal, vUv); o = n.xyz == vec3(0.0) ? vec4(1.0, 1.0, 1.0, 0.0) : vec4(vec3(n.w), 1.0); }`,
      uniforms: { tNormal: { value: gbuffer.normal.texture } },
    }),
  );
  const show = new FullscreenPass(
    new THREE.ShaderMaterial({
      glslVersion: THREE.GLSL3,
      vertexShader: 'out vec2 vUv; void main() { vUv = uv; gl_Position = vec4(position.xy, 0.0, 1.0); }',
      fragmentShader: `precision highp float; uniform sampler2D tAo; in vec2 vUv; out highp vec4 o;
        void main() { vec4 a = texture(tAo, vUv); o = vec4(a.w > 0.5 ? vec3(a.r) : vec3(0.1, 0.1, 0.12), 1.0); }`,
      uniforms: { tAo: { value: out.texture } },
    }),
  );

  // Renders the AO of `mode` into `out` (the G-buffer first).
  const renderAo = (mode) => {
    camera.updateMatrixWorld();
    gbuffer.render(renderer, scene, camera);
    if (mode === 'baked') return baked.render(renderer, out);
    const pass = passes[mode];
    bindFrame(pass.material, gbuffer, camera, settings.radius);
    pass.render(renderer, settings.blur ? raw : out);
    if (!settings.blur) return;
    const u = blur.material.uniforms;
    u.tAo.value = raw.texture;
    u.tPosition.value = gbuffer.position.texture;
    u.uTexel.value.set(1 / width, 1 / height);
    blur.render(renderer, out);
  };
  const draw = () => {
    renderAo(settings.mode);
    show.render(renderer, null);
  };
  const read = (which) => {
    const pixels = new Float32Array(width * height * 4);
    if (which === 'position' || which === 'normal') {
      camera.updateMatrixWorld();
      gbuffer.render(renderer, scene, camera);
      renderer.readRenderTargetPixels(gbuffer[which], 0, 0, width, height, pixels);
    } else {
      renderAo(which);
      renderer.readRenderTargetPixels(out, 0, 0, width, height, pixels);
    }
    return pixels;
  };

  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(target);
  controls.update();
  controls.addEventListener('change', draw);
  const select = document.getElementById('mode');
  select.value = settings.mode;
  select.addEventListener('change', () => {
    settings.mode = select.value;
    draw();
  });
  document.getElementById('info').textContent =
    `radius ${settings.radius.toPrecision(3)}, ${settings.samples} samples, ${settings.slices} slices` +
    (hasAo ? '' : '; the file has no AO section (bake with --ao)');
  draw();
  const readBase64 = (which) => {
    const bytes = new Uint8Array(read(which).buffer);
    let text = '';
    for (let i = 0; i < bytes.length; i += 0x8000)
      text += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
    return btoa(text);
  };
  return { settings, read, readBase64, hasAo, manifest };
}

window.prtAO = { ready: main() };
