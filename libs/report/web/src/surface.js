// The display mesh, flat-shaded in its PRI colours (the same colours and
// lighting as the report's pictures, libs/synth/src/renderer.cpp: two-sided,
// ambient 0.55 + diffuse 0.45 from a light towards (0.35, 0.25, 0.9) in the
// world), weak evidence striped, the selected region and face highlighted.
import {
  BufferAttribute, BufferGeometry, DoubleSide, Mesh, ShaderMaterial, Vector3,
} from 'three';

export const FLAG_UNOBSERVED = 1;
export const FLAG_TWO_VIEWS = 2;
export const FLAG_LOW_TEXTURE = 4;

export const HIGHLIGHT_NONE = 0;
export const HIGHLIGHT_REGION = 1;
export const HIGHLIGHT_PICKED = 2;

const vertexShader = /* glsl */ `
attribute vec3 faceColour;
attribute float faceFlags;
attribute float highlight;
varying vec3 vColour;
varying vec3 vViewPosition;
varying float vWeak;
varying float vHighlight;
void main() {
  vColour = faceColour;
  // Bits 2 (two views only) and 4 (low texture): weak evidence.
  vWeak = floor(mod(faceFlags, 8.0) / 2.0) > 0.0 ? 1.0 : 0.0;
  vHighlight = highlight;
  vec4 mv = modelViewMatrix * vec4(position, 1.0);
  vViewPosition = mv.xyz;
  gl_Position = projectionMatrix * mv;
}`;

const fragmentShader = /* glsl */ `
uniform float markWeak;
uniform vec3 light;  // towards the light, world frame, unit
varying vec3 vColour;
varying vec3 vViewPosition;
varying float vWeak;
varying float vHighlight;
void main() {
  // Flat shading: the face normal from the screen-space derivatives.
  vec3 n = normalize(cross(dFdx(vViewPosition), dFdy(vViewPosition)));
  if (dot(n, vViewPosition) > 0.0) n = -n;  // two-sided: the side facing the eye
  vec3 l = normalize((viewMatrix * vec4(light, 0.0)).xyz);
  float diffuse = max(0.0, dot(n, l));
  vec3 base = vColour;
  if (vHighlight > 1.5) base = vec3(0.0, 0.85, 1.0);
  else if (vHighlight > 0.5) base = vec3(1.0, 0.0, 1.0);
  vec3 c = base * (0.55 + 0.45 * diffuse);
  if (markWeak > 0.5 && vWeak > 0.5 && vHighlight < 0.5) {
    // Thin diagonal stripes in screen space, 2 of every 8 pixels darker.
    if (mod(gl_FragCoord.x + gl_FragCoord.y, 8.0) < 2.0) c = mix(c, vec3(0.1, 0.1, 0.18), 0.55);
  }
  gl_FragColor = vec4(c, 1.0);
}`;

// A non-indexed geometry (three vertices per face) so that every face has
// its own colour, flags and highlight.
export function buildSurface(data) {
  const positions = data.array('positions');
  const indices = data.array('indices');
  const colours = data.array('colours');
  const flags = data.array('display_flags');
  const faces = indices.length / 3;
  const xyz = new Float32Array(faces * 9);
  const rgb = new Uint8Array(faces * 9);
  const faceFlags = new Uint8Array(faces * 3);
  for (let f = 0; f < faces; ++f) {
    for (let k = 0; k < 3; ++k) {
      const v = indices[3 * f + k];
      const o = 9 * f + 3 * k;
      xyz[o] = positions[3 * v];
      xyz[o + 1] = positions[3 * v + 1];
      xyz[o + 2] = positions[3 * v + 2];
      rgb[o] = colours[3 * f];
      rgb[o + 1] = colours[3 * f + 1];
      rgb[o + 2] = colours[3 * f + 2];
      faceFlags[3 * f + k] = flags[f];
    }
  }
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(xyz, 3));
  geometry.setAttribute('faceColour', new BufferAttribute(rgb, 3, true));
  geometry.setAttribute('faceFlags', new BufferAttribute(faceFlags, 1));
  geometry.setAttribute('highlight', new BufferAttribute(new Uint8Array(faces * 3), 1));
  geometry.computeBoundingSphere();
  geometry.computeBoundingBox();
  const material = new ShaderMaterial({
    vertexShader,
    fragmentShader,
    uniforms: { markWeak: { value: 1.0 }, light: { value: new Vector3(0.35, 0.25, 0.9).normalize() } },
    side: DoubleSide,  // meshes of any orientation
  });
  const mesh = new Mesh(geometry, material);

  let highlighted = [];
  return {
    mesh,
    faces,
    setMarkWeak(on) {
      material.uniforms.markWeak.value = on ? 1.0 : 0.0;
    },
    // Highlights exactly the display faces given (and clears the others
    // highlighted before): a list of [face, HIGHLIGHT_*].
    setHighlights(list) {
      const attribute = geometry.getAttribute('highlight');
      for (const f of highlighted) attribute.array.fill(HIGHLIGHT_NONE, 3 * f, 3 * f + 3);
      highlighted = [];
      for (const [f, kind] of list) {
        attribute.array.fill(kind, 3 * f, 3 * f + 3);
        highlighted.push(f);
      }
      attribute.needsUpdate = true;
    },
  };
}
