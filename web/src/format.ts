// Numbers as the user reads them: three significant digits, plain for everyday magnitudes.

/** Three significant digits: 0.0005, 0.0123, 4.57, 1230, 1.23e-7. */
export function sig3(v: number): string {
  if (!Number.isFinite(v)) return String(v);
  const a = Math.abs(v);
  if (a === 0) return '0';
  if (a >= 1e-4 && a < 1e5) return String(Number(v.toPrecision(3)));
  return v.toExponential(2);
}
