// The report's data (viewer/report_data.js sets window.MESHNBV_REPORT):
// JSON with binary arrays in base64, decoded on first use, so that the
// per-original-face arrays of a large mesh cost nothing until a face is
// picked.

function bytesOf(base64) {
  if (typeof Uint8Array.fromBase64 === 'function') return Uint8Array.fromBase64(base64);
  const text = atob(base64);
  const bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i);
  return bytes;
}

const TYPES = {
  Float32Array, Uint32Array, Uint16Array, Uint8Array,
};

// One typed array of the data: { type: 'Float32Array', count, base64 }.
function decode(entry) {
  const Type = TYPES[entry.type];
  if (!Type) throw new Error(`report data: unknown array type ${entry.type}`);
  const bytes = bytesOf(entry.base64);
  if (bytes.byteLength !== entry.count * Type.BYTES_PER_ELEMENT) {
    throw new Error(`report data: array of ${bytes.byteLength} bytes, expected ${entry.count} ${entry.type} elements`);
  }
  return new Type(bytes.buffer, bytes.byteOffset, entry.count);
}

// The report data with `array(name)`: each array decoded once, when first asked for.
export function reportData(raw) {
  if (!raw || raw.format !== 'meshnbv-report-view') {
    throw new Error('report data missing or not a MeshNBV report view (viewer/report_data.js)');
  }
  const decoded = new Map();
  return {
    ...raw,
    array(name) {
      if (!decoded.has(name)) {
        const entry = raw.arrays[name];
        if (!entry) throw new Error(`report data: no array ${name}`);
        decoded.set(name, decode(entry));
      }
      return decoded.get(name);
    },
  };
}
