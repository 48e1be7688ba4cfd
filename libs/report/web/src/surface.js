// The display mesh, flat-shaded in its PRI colours (the same colours and
// lighting as the report's pictures, libs/synth/src/renderer.cpp: two-sided,
// ambient 0.55 + diffuse 0.45 from a light towards (0.35, 0.25, 0.9) in the
// world), weak evidence striped, the selected region and face highlighted.
// Three vertices of its own per face (non-indexed), so that each face has
// its own colour, flags, normal and highlight.
import {
  BufferAttribute, BufferGeometry, DoubleSide, Mesh, ShaderMaterial, Vector3,
} from 'three';

export const FLAG_UNOBSERVED = 1;
export const FLAG_TWO_VIEWS = 2;
export const FLAG_LOW_TEXTURE = 4;

export const HIGHLIGHT_NONE = 0;
export const HIGHLIGHT_REGION = 1;
export const HIGHLIGHT_PICKED = 2;

// Shaded per face in the vertex shader, from the face's normal (an
// attribute, 8 bits a component, with the flags and highlight in the
// fourth; every attribute 4-byte aligned): the three corners of a face
// compute the same colour (a plane faces the eye the same way at each of
// its points, so the two-sided test is exact there), and the fragment
// shader only copies it and stripes. Shading per fragment (the normal from
// screen-space derivatives) made a frame of the interaction mesh about a
// third slower in software WebGL (bench/results/report/report_3d.md).
const vertexShader = /* glsl */ `
uniform float markWeak;
uniform vec3 light;  // towards the light, world frame, unit
attribute vec4 faceColour;  // rgb; a unused (4-byte aligned)
attribute vec4 faceNormal;  // xyz: the face's normal; w * 127: its flags + 8 * its highlight
varying vec3 vColour;
varying float vStripes;
void main() {
  float code = floor(faceNormal.w * 127.0 + 0.5);
  float highlight = floor(code / 8.0);
  float faceFlags = mod(code, 8.0);
  vec3 base = highlight > 1.5 ? vec3(0.0, 0.85, 1.0) : highlight > 0.5 ? vec3(1.0, 0.0, 1.0) : faceColour.rgb;
  // Bits 2 (two views only) and 4 (low texture): weak evidence.
  float weak = floor(mod(faceFlags, 8.0) / 2.0) > 0.0 ? 1.0 : 0.0;
  vStripes = markWeak * weak * (highlight > 0.5 ? 0.0 : 1.0);
  vec4 world = modelMatrix * vec4(position, 1.0);
  float len = length(faceNormal.xyz);
  vec3 n = len > 0.0 ? faceNormal.xyz / len : vec3(0.0);  // a degenerate face: ambient only
  if (dot(n, world.xyz - cameraPosition) > 0.0) n = -n;  // two-sided: the side facing the eye
  vColour = base * (0.55 + 0.45 * max(0.0, dot(n, light)));
  gl_Position = projectionMatrix * viewMatrix * world;
}`;

const fragmentShader = /* glsl */ `
varying vec3 vColour;
varying float vStripes;
void main() {
  vec3 c = vColour;
  // Thin diagonal stripes in screen space, 2 of every 8 pixels darker.
  if (vStripes > 0.5 && mod(gl_FragCoord.x + gl_FragCoord.y, 8.0) < 2.0) c = mix(c, vec3(0.1, 0.1, 0.18), 0.55);
  gl_FragColor = vec4(c, 1.0);
}`;

// The material both levels of detail share (so that the stripe toggle
// applies to both).
export function surfaceMaterial() {
  return new ShaderMaterial({
    vertexShader,
    fragmentShader,
    uniforms: { markWeak: { value: 1.0 }, light: { value: new Vector3(0.35, 0.25, 0.9).normalize() } },
    side: DoubleSide,  // meshes of any orientation
  });
}

// The surface of a mesh: `positions` xyz per vertex, `indices` three
// vertices per face, `colours` rgb per face, `flags` FLAG_* per face.
export function buildSurface({ positions, indices, colours, flags }, material) {
  const faces = indices.length / 3;
  const xyz = new Float32Array(faces * 9);
  const rgb = new Uint8Array(faces * 12);
  const faceNormal = new Int8Array(faces * 12);
  for (let f = 0; f < faces; ++f) {
    const a = 3 * indices[3 * f];
    const b = 3 * indices[3 * f + 1];
    const c = 3 * indices[3 * f + 2];
    const ux = positions[b] - positions[a];
    const uy = positions[b + 1] - positions[a + 1];
    const uz = positions[b + 2] - positions[a + 2];
    const wx = positions[c] - positions[a];
    const wy = positions[c + 1] - positions[a + 1];
    const wz = positions[c + 2] - positions[a + 2];
    const nx = uy * wz - uz * wy;
    const ny = uz * wx - ux * wz;
    const nz = ux * wy - uy * wx;
    const scale = 127 / (Math.hypot(nx, ny, nz) || 1);
    for (let k = 0; k < 3; ++k) {
      const v = 3 * indices[3 * f + k];
      const o = 9 * f + 3 * k;
      xyz[o] = positions[v];
      xyz[o + 1] = positions[v + 1];
      xyz[o + 2] = positions[v + 2];
      const o4 = 12 * f + 4 * k;
      rgb[o4] = colours[3 * f];
      rgb[o4 + 1] = colours[3 * f + 1];
      rgb[o4 + 2] = colours[3 * f + 2];
      faceNormal[o4] = Math.round(nx * scale);
      faceNormal[o4 + 1] = Math.round(ny * scale);
      faceNormal[o4 + 2] = Math.round(nz * scale);
      faceNormal[o4 + 3] = flags[f];
    }
  }
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(xyz, 3));
  geometry.setAttribute('faceColour', new BufferAttribute(rgb, 4, true));
  geometry.setAttribute('faceNormal', new BufferAttribute(faceNormal, 4, true));
  geometry.computeBoundingSphere();
  geometry.computeBoundingBox();
  const mesh = new Mesh(geometry, material);

  let highlighted = [];
  const mark = (array, f, code) => {
    for (let k = 0; k < 3; ++k) array[12 * f + 4 * k + 3] = code;
  };
  return {
    mesh,
    faces,
    // Highlights exactly the faces given (and clears the others
    // highlighted before): a list of [face, HIGHLIGHT_*].
    setHighlights(list) {
      const attribute = geometry.getAttribute('faceNormal');
      for (const f of highlighted) mark(attribute.array, f, flags[f]);
      highlighted = [];
      for (const [f, kind] of list) {
        mark(attribute.array, f, flags[f] + 8 * kind);
        highlighted.push(f);
      }
      attribute.needsUpdate = true;
    },
  };
}

export function setMarkWeak(material, on) {
  material.uniforms.markWeak.value = on ? 1.0 : 0.0;
}

// The display mesh's arrays, for buildSurface.
export function displayArrays(data) {
  return {
    positions: data.array('positions'),
    indices: data.array('indices'),
    colours: data.array('colours'),
    flags: data.array('display_flags'),
  };
}

// The interaction mesh's arrays (data.interaction): its vertices are display
// vertices, so it shares the display mesh's positions.
export function interactionArrays(data) {
  const vertices = data.array('interaction_vertices');
  const local = data.array('interaction_indices');
  const indices = new Uint32Array(local.length);
  for (let i = 0; i < local.length; ++i) indices[i] = vertices[local[i]];
  return {
    positions: data.array('positions'),
    indices,
    colours: data.array('interaction_colours'),
    flags: data.array('interaction_flags'),
  };
}
