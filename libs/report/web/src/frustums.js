// Camera frustums as lines: apex to the four image corners at a depth, and
// the rectangle of the corners (as the report's pictures draw them).
import { BufferAttribute, BufferGeometry, LineBasicMaterial, LineSegments, Vector3 } from 'three';
import { vec } from './camera_math.js';

// World (local-frame) positions of the image's outer corners at z-depth `depth`.
export function frustumCorners(view, centre, depth) {
  const R = view.R;
  const right = vec(R[0]);
  const down = vec(R[1]);
  const forward = vec(R[2]);
  const corners = [
    [-0.5, -0.5], [view.width - 0.5, -0.5], [view.width - 0.5, view.height - 0.5], [-0.5, view.height - 0.5],
  ];
  return corners.map(([u, v]) => {
    const x = ((u - view.cx) / view.fx) * depth;
    const y = ((v - view.cy) / view.fy) * depth;
    return centre.clone().addScaledVector(right, x).addScaledVector(down, y).addScaledVector(forward, depth);
  });
}

// One LineSegments for many frustums: [{ view, centre (local Vector3), colour [r,g,b] 0..255 }].
export function buildFrustums(list) {
  const points = [];
  const colours = [];
  for (const { view, centre, colour } of list) {
    const corners = frustumCorners(view, centre, view.depth);
    for (let k = 0; k < 4; ++k) {
      points.push(centre, corners[k], corners[k], corners[(k + 1) % 4]);
    }
    for (let i = 0; i < 16; ++i) colours.push(colour[0] / 255, colour[1] / 255, colour[2] / 255);
  }
  const xyz = new Float32Array(points.length * 3);
  points.forEach((p, i) => p.toArray(xyz, 3 * i));
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(xyz, 3));
  geometry.setAttribute('color', new BufferAttribute(new Float32Array(colours), 3));
  return new LineSegments(geometry, new LineBasicMaterial({ vertexColors: true }));
}

export function suggestionColour(i, n) {
  const t = n > 1 ? i / (n - 1) : 0;
  return [255, Math.round(200 * t), 0];
}

export const EXISTING_COLOUR = [40, 90, 230];

export function centreOf(view, origin) {
  return new Vector3(view.centre[0] - origin[0], view.centre[1] - origin[1], view.centre[2] - origin[2]);
}
