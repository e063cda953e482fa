// Colour maths of the preview: the page's views are 8-bit sRGB, so edits are previewed on those values (the export
// runs the library's own recolour on the stored samples).

const SRGB_TO_LINEAR = new Float32Array(256);
for (let i = 0; i < 256; ++i) {
  const c = i / 255;
  SRGB_TO_LINEAR[i] = c <= 0.04045 ? c / 12.92 : Math.pow((c + 0.055) / 1.055, 2.4);
}
const ENCODE_STEPS = 4096;
const LINEAR_TO_SRGB8 = new Uint8ClampedArray(ENCODE_STEPS + 1);
for (let i = 0; i <= ENCODE_STEPS; ++i) {
  const c = i / ENCODE_STEPS;
  LINEAR_TO_SRGB8[i] = Math.round(255 * (c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055));
}
function encode(linear) {
  const clamped = linear < 0 ? 0 : linear > 1 ? 1 : linear;
  return LINEAR_TO_SRGB8[Math.round(clamped * ENCODE_STEPS)];
}

// CIE Lab (D65) helpers.
const WHITE = [0.95047, 1.0, 1.08883];
function labF(t) { return t > 0.008856 ? Math.cbrt(t) : 7.787 * t + 16 / 116; }
function labFInverse(t) { return t > 0.206893 ? t * t * t : (t - 16 / 116) / 7.787; }

// out[0..2] = the edited 8-bit colour of (r, g, b), blending `strength` (0..1) of the edit.
function adjustLch(r, g, b, edit, strength, out) {
  const lr = SRGB_TO_LINEAR[r], lg = SRGB_TO_LINEAR[g], lb = SRGB_TO_LINEAR[b];
  const fx = labF((0.4124 * lr + 0.3576 * lg + 0.1805 * lb) / WHITE[0]);
  const fy = labF(0.2126 * lr + 0.7152 * lg + 0.0722 * lb);
  const fz = labF((0.0193 * lr + 0.1192 * lg + 0.9505 * lb) / WHITE[2]);
  const L = (116 * fy - 16) * edit.value;
  const a = 500 * (fx - fy), bb = 200 * (fy - fz);
  const a2 = (a * edit.cos - bb * edit.sin) * edit.saturation;
  const b2 = (a * edit.sin + bb * edit.cos) * edit.saturation;
  const gy = (L + 16) / 116;
  const X = WHITE[0] * labFInverse(gy + a2 / 500), Y = labFInverse(gy), Z = WHITE[2] * labFInverse(gy - b2 / 200);
  const nr = encode(3.2406 * X - 1.5372 * Y - 0.4986 * Z);
  const ng = encode(-0.9689 * X + 1.8758 * Y + 0.0415 * Z);
  const nb = encode(0.0557 * X - 0.204 * Y + 1.057 * Z);
  out[0] = r + (nr - r) * strength;
  out[1] = g + (ng - g) * strength;
  out[2] = b + (nb - b) * strength;
}

function clampByte(t) { return t < 0 ? 0 : t > 255 ? 255 : t; }

function adjustHsv(r, g, b, edit, strength, out) {
  const max = Math.max(r, g, b), min = Math.min(r, g, b), delta = max - min;
  let h = 0;
  if (delta > 0) {
    if (max === r) h = 60 * (((g - b) / delta) % 6);
    else if (max === g) h = 60 * ((b - r) / delta + 2);
    else h = 60 * ((r - g) / delta + 4);
  }
  h = (((h + edit.hue) % 360) + 360) % 360;
  const s = Math.min(1, (max > 0 ? delta / max : 0) * edit.saturation);
  const v = max * edit.value;
  const c = v * s, x = c * (1 - Math.abs(((h / 60) % 2) - 1)), m = v - c;
  let nr = 0, ng = 0, nb = 0;  // (nr, ng, nb) - m by the hue's sector
  switch (Math.floor(h / 60) % 6) {
    case 0: nr = c; ng = x; break;
    case 1: nr = x; ng = c; break;
    case 2: ng = c; nb = x; break;
    case 3: ng = x; nb = c; break;
    case 4: nr = x; nb = c; break;
    default: nr = c; nb = x;
  }
  out[0] = r + (clampByte(nr + m) - r) * strength;
  out[1] = g + (clampByte(ng + m) - g) * strength;
  out[2] = b + (clampByte(nb + m) - b) * strength;
}

// The edit as the colour functions want it (angles precomputed); null when it changes nothing.
export function prepareEdit(params) {
  if (params.hue === 0 && params.saturation === 1 && params.value === 1) return null;
  const radians = (params.hue * Math.PI) / 180;
  return { ...params, cos: Math.cos(radians), sin: Math.sin(radians),
           apply: params.space === 'hsv' ? adjustHsv : adjustLch };
}

// The TURBO colour map (as OpenCV draws the depth elsewhere in lfsp) as a 256-entry RGB table, from the polynomial
// approximation published with Turbo by Google (Apache 2.0).
export const TURBO = (() => {
  const table = new Uint8Array(256 * 3);
  for (let i = 0; i < 256; ++i) {
    const t = i / 255;
    const r = 0.13572138 + t * (4.6153926 + t * (-42.66032258 + t * (132.13108234 + t * (-152.94239396 + t * 59.28637943))));
    const g = 0.09140261 + t * (2.19418839 + t * (4.84296658 + t * (-14.18503333 + t * (4.27729857 + t * 2.82956604))));
    const b = 0.1066733 + t * (12.64194608 + t * (-60.58204836 + t * (110.36276771 + t * (-89.90310912 + t * 27.34824973))));
    table[3 * i] = Math.max(0, Math.min(255, Math.round(255 * r)));
    table[3 * i + 1] = Math.max(0, Math.min(255, Math.round(255 * g)));
    table[3 * i + 2] = Math.max(0, Math.min(255, Math.round(255 * b)));
  }
  return table;
})();
