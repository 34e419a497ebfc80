// web/background.js — the environment map behind the scene, as `prt relight` draws it
// (relight/renderer.h): the ray through each pixel looks up the lat-long map in direction Mᵀd
// when the lighting is rotated by M, so the visible sky turns with the light; linear radiance
// through the same exposure, filmic curve and sRGB step as the surfaces (prt-relight.js).
import * as THREE from 'three';
import { TONE_MAP_GLSL } from './prt-relight.js';

const VERTEX = /* glsl */ `
in vec3 position;
out vec2 vNdc;
void main() {
  vNdc = position.xy;
  gl_Position = vec4(position.xy, 1.0, 1.0);
}
`;

const FRAGMENT = /* glsl */ `
precision highp float;
precision highp int;
in vec2 vNdc;
uniform sampler2D uEnvironment;
uniform vec2 uTanHalfFov; // tan(yfov/2)·aspect, tan(yfov/2)
uniform mat4 uCameraWorld;
uniform mat3 uRotationTransposed;
uniform float uExposure;
uniform int uShow;
out vec4 outColor;
${TONE_MAP_GLSL}
void main() {
  if (uShow == 0) { outColor = vec4(0.0, 0.0, 0.0, 1.0); return; }
  vec3 view = vec3(vNdc * uTanHalfFov, -1.0); // the camera looks down its −Z
  vec3 d = normalize((uCameraWorld * vec4(view, 0.0)).xyz);
  vec3 s = uRotationTransposed * d;
  float u = 0.5 + atan(s.z, s.x) / 6.283185307179586;
  float v = acos(clamp(s.y, -1.0, 1.0)) / 3.141592653589793;
  vec3 radiance = texture(uEnvironment, vec2(u, v)).rgb;
  outColor = vec4(prtToneMap(radiance, uExposure), 1.0);
}
`;

// data: Uint16Array of float16 RGBA texels (row 0 the zenith).
export function createBackground(data, width, height) {
  const texture = new THREE.DataTexture(data, width, height, THREE.RGBAFormat, THREE.HalfFloatType);
  texture.minFilter = texture.magFilter = THREE.LinearFilter;
  texture.wrapS = THREE.RepeatWrapping;
  texture.wrapT = THREE.ClampToEdgeWrapping;
  texture.generateMipmaps = false;
  texture.needsUpdate = true;
  const material = new THREE.RawShaderMaterial({
    glslVersion: THREE.GLSL3,
    vertexShader: VERTEX,
    fragmentShader: FRAGMENT,
    depthTest: false,
    depthWrite: false,
    uniforms: {
      uEnvironment: { value: texture },
      uTanHalfFov: { value: new THREE.Vector2() },
      uCameraWorld: { value: new THREE.Matrix4() },
      uRotationTransposed: { value: new THREE.Matrix3() },
      uExposure: { value: 0 },
      uShow: { value: 1 },
    },
  });
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array([-1, -1, 0, 3, -1, 0, -1, 3, 0]), 3));
  const mesh = new THREE.Mesh(geometry, material);
  mesh.frustumCulled = false;
  const scene = new THREE.Scene();
  scene.add(mesh);
  return {
    scene,
    material,
    // M: row-major 3×3 lighting rotation.
    update(camera, rotation, exposureEv, show) {
      const t = Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2);
      material.uniforms.uTanHalfFov.value.set(t * camera.aspect, t);
      material.uniforms.uCameraWorld.value.copy(camera.matrixWorld);
      material.uniforms.uRotationTransposed.value.set(...rotation).transpose();
      material.uniforms.uExposure.value = exposureEv;
      material.uniforms.uShow.value = show ? 1 : 0;
    },
  };
}
