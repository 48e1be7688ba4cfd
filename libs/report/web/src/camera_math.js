// Our camera convention (docs/conventions.md): x_cam = R X + t, camera x
// right, y down, z forward; pixel centres at integers. three.js cameras look
// down their -z with y up, so a view's three.js basis is (right, -down,
// -forward), the rows of R negated as needed.
import { Matrix4, Quaternion, Vector3 } from 'three';

export function vec(a) {
  return new Vector3(a[0], a[1], a[2]);
}

// The rotation of a three.js camera at the pose of a view with rotation R (3x3 rows).
export function quaternionOf(R) {
  const right = vec(R[0]);
  const up = vec(R[1]).negate();
  const back = vec(R[2]).negate();
  return new Quaternion().setFromRotationMatrix(new Matrix4().makeBasis(right, up, back));
}

// The vertical field of view (degrees) of intrinsics { fy, height }.
export function verticalFov(view) {
  return (2 * Math.atan(view.height / (2 * view.fy)) * 180) / Math.PI;
}

// The projection of a pinhole view (fx, fy, cx, cy, width x height) on a
// canvas of `canvasWidth` x `canvasHeight`: the whole image fitted into the
// canvas, centred, at the view's own aspect and principal point. Returns the
// matrix and the image's rectangle on the canvas (CSS pixels).
export function intrinsicProjection(view, canvasWidth, canvasHeight, near, far) {
  const s = Math.min(canvasWidth / view.width, canvasHeight / view.height);
  const offX = (canvasWidth - view.width * s) / 2;
  const offY = (canvasHeight - view.height * s) / 2;
  // NDC x = a * x/(-z) + c0; NDC y = e * y/(-z) + d (three.js camera frame).
  const a = (2 * s * view.fx) / canvasWidth;
  const c0 = (2 * (offX + (view.cx + 0.5) * s)) / canvasWidth - 1;
  const e = (2 * s * view.fy) / canvasHeight;
  const d = 1 - (2 * (offY + (view.cy + 0.5) * s)) / canvasHeight;
  const m = new Matrix4().set(
    a, 0, -c0, 0,
    0, e, -d, 0,
    0, 0, -(far + near) / (far - near), (-2 * far * near) / (far - near),
    0, 0, -1, 0,
  );
  return { matrix: m, rect: { x: offX, y: offY, width: view.width * s, height: view.height * s } };
}

// The distance from `centre` along `direction` at which every point of
// `points` (relative to centre) fits into a view of vertical field of view
// `fov` (degrees) and `aspect`, within `margin` (0.9: 90 % of the view).
export function fitDistance(points, direction, up, fov, aspect, margin = 0.9) {
  const back = direction.clone().normalize();
  const right = new Vector3().crossVectors(up, back).normalize();
  const trueUp = new Vector3().crossVectors(back, right);
  const tanV = Math.tan(((fov / 2) * Math.PI) / 180) * margin;
  const tanH = tanV * aspect;
  let distance = 0;
  for (const p of points) {
    const along = p.dot(back);
    distance = Math.max(distance, along + Math.abs(p.dot(right)) / tanH, along + Math.abs(p.dot(trueUp)) / tanV);
  }
  return distance;
}
