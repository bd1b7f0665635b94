// Numbers as the user reads them: three significant digits, plain for everyday magnitudes.

/** Three significant digits: 0.0005, 0.0123, 4.57, 1230, 1.23e-7. */
export function sig3(v: number): string {
  if (!Number.isFinite(v)) return String(v);
  const a = Math.abs(v);
  if (a === 0) return '0';
  if (a >= 1e-4 && a < 1e5) return String(Number(v.toPrecision(3)));
  return v.toExponential(2);
}

/** Significant digits of a panel field's number (the fields are narrow: 1/60 reads 0.01667). */
export const FIELD_DIGITS = 4;

/**
 * A number in a panel field: at most FIELD_DIGITS significant digits, without float noise
 * (0.35000000000000003 → "0.35", 0.20254629629629634 → "0.2025", 1e-6 → "0.000001"). Only the
 * text: the value kept is the one given, unless the user types another.
 */
export function fieldText(v: number, digits = FIELD_DIGITS): string {
  if (!Number.isFinite(v)) return String(v);
  if (v === 0) return '0';
  return String(Number(v.toPrecision(digits)));
}

/**
 * The volume as the HUD reads it ("V 2.45 m³"): an open surface (cloth-like) encloses none, and
 * the signed volume of its triangles (e.g. −1.08 m³ for a draped cloth) means nothing to the user.
 */
export function volumeText(volume: number, closed: boolean): string {
  return closed ? `V ${sig3(volume)} m³` : 'open surface (no volume)';
}

/** Three significant digits as `toPrecision` writes them (0.0167, 0.500), '?' for a value not known: the worker's messages. */
export function precision3(t: number | undefined): string {
  return t === undefined ? '?' : t.toPrecision(3);
}

/** A fraction as a percentage: one decimal below 1 %, none above ("0.5 %", "12 %"). */
export function percent(x: number): string {
  return `${(100 * x).toFixed(x < 0.01 ? 1 : 0)} %`;
}
