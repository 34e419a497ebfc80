// web/passes/ao_common.js — what the screen-space AO passes share: the G-buffer (world-space
// position and normal per pixel, float32), the full-screen pass, and the per-pixel noise.
//
// G-buffer: two RGBA32F render targets of the canvas size. position: world xyz, w = 1 where the
// front of a surface (the side its vertex normals face) covers the pixel, 2 where its back side
// does, 0 elsewhere; normal: unit world normal xyz (interpolated vertex
// normals, flipped toward the camera), w = the per-vertex value of the file's AO section
// (baked AO or obscurance), interpolated. The AO passes transform them to view space with the
// camera's matrices (uniforms uView, uProj) and write AO in the red channel (1 = open).
import * as THREE from 'three';

export function floatTarget(width, height) {
  return new THREE.WebGLRenderTarget(width, height, {
    type: THREE.FloatType,
    format: THREE.RGBAFormat,
    minFilter: THREE.NearestFilter,
    magFilter: THREE.NearestFilter,
    depthBuffer: true,
  });
}

const gbufferVertex = /* glsl */ `
in float ao;
out vec3 vWorld;
out vec3 vNormal;
out float vAo;
void main() {
  vec4 w = modelMatrix * vec4(position, 1.0);
  vWorld = w.xyz;
  vNormal = normalize(mat3(modelMatrix) * normal);
  vAo = ao;
  gl_Position = projectionMatrix * viewMatrix * w;
}`;

function gbufferMaterial(which) {
  const body =
    which === 'position'
      ? 'outColor = vec4(vWorld, dot(vNormal, cameraPosition - vWorld) < 0.0 ? 2.0 : 1.0);'
      : `vec3 n = normalize(vNormal);
         if (dot(n, cameraPosition - vWorld) < 0.0) n = -n;
         outColor = vec4(n, vAo);`;
  return new THREE.ShaderMaterial({
    glslVersion: THREE.GLSL3,
    vertexShader: gbufferVertex,
    fragmentShader: `precision highp float;
in vec3 vWorld; in vec3 vNormal; in float vAo;
out highp vec4 outColor;
void main() { ${body} }`,
    side: THREE.DoubleSide,
  });
}

// The two G-buffer targets of `scene` seen by `camera`.
export class GBuffer {
  constructor(width, height) {
    this.position = floatTarget(width, height);
    this.normal = floatTarget(width, height);
    this.positionMaterial = gbufferMaterial('position');
    this.normalMaterial = gbufferMaterial('normal');
  }
  render(renderer, scene, camera) {
    const clear = renderer.getClearColor(new THREE.Color());
    const alpha = renderer.getClearAlpha();
    renderer.setClearColor(0x000000, 0);
    for (const [target, material] of [
      [this.position, this.positionMaterial],
      [this.normal, this.normalMaterial],
    ]) {
      scene.overrideMaterial = material;
      renderer.setRenderTarget(target);
      renderer.clear();
      renderer.render(scene, camera);
    }
    scene.overrideMaterial = null;
    renderer.setRenderTarget(null);
    renderer.setClearColor(clear, alpha);
  }
}

// GLSL shared by the AO passes: view-space position and normal of a pixel, and a per-pixel
// hash on a 4×4 tile (the classic rotation-noise tile, removed by blurPass).
export const aoHeader = /* glsl */ `precision highp float;
uniform sampler2D tPosition;
uniform sampler2D tNormal;
uniform mat4 uView;
uniform mat4 uProj;
uniform float uRadius;
in vec2 vUv;
out highp vec4 outColor;
const float PI = 3.14159265358979;
bool covered(vec2 uv) { return texture(tPosition, uv).w > 0.5; }
vec3 viewPosition(vec2 uv) { return (uView * vec4(texture(tPosition, uv).xyz, 1.0)).xyz; }
vec3 viewNormal(vec2 uv) { return normalize(mat3(uView) * texture(tNormal, uv).xyz); }
vec2 project(vec3 p) { vec4 c = uProj * vec4(p, 1.0); return c.xy / c.w * 0.5 + 0.5; }
bool onScreen(vec2 uv) { return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0))); }
float tileNoise(float salt) {
  vec2 t = mod(floor(gl_FragCoord.xy), 4.0);
  return fract(sin(dot(t + salt, vec2(12.9898, 78.233))) * 43758.5453);
}`;

export const fullscreenVertex = /* glsl */ `
out vec2 vUv;
void main() { vUv = uv; gl_Position = vec4(position.xy, 0.0, 1.0); }`;

// A full-screen pass: `material` drawn over a 2×2 quad into `target` (null: the canvas).
export class FullscreenPass {
  constructor(material) {
    this.material = material;
    this.scene = new THREE.Scene();
    this.camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
    this.scene.add(new THREE.Mesh(new THREE.PlaneGeometry(2, 2), material));
  }
  render(renderer, target) {
    renderer.setRenderTarget(target);
    renderer.render(this.scene, this.camera);
    renderer.setRenderTarget(null);
  }
}

export function aoMaterial(fragmentBody, uniforms) {
  return new THREE.ShaderMaterial({
    glslVersion: THREE.GLSL3,
    vertexShader: fullscreenVertex,
    fragmentShader: aoHeader + fragmentBody,
    uniforms: {
      tPosition: { value: null },
      tNormal: { value: null },
      uView: { value: new THREE.Matrix4() },
      uProj: { value: new THREE.Matrix4() },
      uRadius: { value: 1 },
      ...uniforms,
    },
    depthTest: false,
    depthWrite: false,
  });
}

// Sets the G-buffer and camera uniforms of an AO material.
export function bindFrame(material, gbuffer, camera, radius) {
  const u = material.uniforms;
  u.tPosition.value = gbuffer.position.texture;
  u.tNormal.value = gbuffer.normal.texture;
  u.uView.value.copy(camera.matrixWorldInverse);
  u.uProj.value.copy(camera.projectionMatrix);
  u.uRadius.value = radius;
}

// The 4×4 box blur of the noise tile over covered pixels (background stays 1).
export function blurMaterial() {
  return new THREE.ShaderMaterial({
    glslVersion: THREE.GLSL3,
    vertexShader: fullscreenVertex,
    fragmentShader: /* glsl */ `precision highp float;
uniform sampler2D tAo;
uniform sampler2D tPosition;
uniform vec2 uTexel;
in vec2 vUv;
out highp vec4 outColor;
void main() {
  if (texture(tPosition, vUv).w < 0.5) { outColor = vec4(1.0, 1.0, 1.0, 0.0); return; }
  float sum = 0.0, count = 0.0;
  for (int y = -2; y < 2; ++y)
    for (int x = -2; x < 2; ++x) {
      vec2 uv = vUv + vec2(x, y) * uTexel;
      if (texture(tPosition, uv).w < 0.5) continue;
      sum += texture(tAo, uv).r;
      count += 1.0;
    }
  float ao = count > 0.0 ? sum / count : texture(tAo, vUv).r;
  outColor = vec4(ao, ao, ao, 1.0);
}`,
    uniforms: { tAo: { value: null }, tPosition: { value: null }, uTexel: { value: new THREE.Vector2() } },
    depthTest: false,
    depthWrite: false,
  });
}
