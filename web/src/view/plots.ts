// Live plots of volume, pressure and energies over the last seconds, on a small 2D canvas.

export interface Series {
  label: string;
  color: string;
  values: number[];
  /** Series of one group (the energies) share one noise floor: see `draw`. */
  group?: string;
  /** Shown after the label while the latest value is negative: why it can be. */
  whyNegative?: string;
  /**
   * Drawn relative to its first value since the plots were cleared (a new model): the core's gas
   * energy −nRT ln(V/V0) + P_ref (V − V0) counts from the mesh as loaded, before the gas inflated
   * it (−5.9 J for the modeler's mushroom as shown); what a user reads is the change from there.
   */
  fromFirst?: boolean;
}

/**
 * A variation smaller than this fraction of its group's magnitude is drawn flat: the plots show
 * physics, not round-off (a resting body's kinetic energy of 1e-22 J next to 30 J of gas).
 */
export const NOISE_FRACTION = 1e-3;
/** Pixels at the top of each row for its label (the curve stays below it). */
const LABEL_PX = 12;

export class Plots {
  private readonly ctx: CanvasRenderingContext2D;
  readonly series: Series[] = [
    { label: 'volume m³', color: '#7fd1ff', values: [] },
    { label: 'pressure Pa', color: '#ffd27f', values: [] },
    { label: 'kinetic J', color: '#ff8f8f', values: [], group: 'energy' },
    { label: 'elastic J', color: '#9dff8f', values: [], group: 'energy', whyNegative: 'below 0: frozen under a load' },
    { label: 'gas J', color: '#d59dff', values: [], group: 'energy', fromFirst: true, whyNegative: 'below 0: the gas has expanded' },
  ];
  private times: number[] = [];
  /** The first value of each `fromFirst` series since the last clear (NaN: none yet). */
  private readonly first = this.series.map(() => NaN);

  constructor(readonly canvas: HTMLCanvasElement, private readonly windowSeconds = 10) {
    this.ctx = canvas.getContext('2d')!;
  }

  /** The values of `s` as drawn (a `fromFirst` series: relative to its first). */
  shown(s: Series): number[] { return s.values; }

  clear(): void {
    this.times = [];
    for (const s of this.series) s.values = [];
    this.first.fill(NaN);
  }

  push(time: number, values: number[]): void {
    if (this.times.length && time < this.times[this.times.length - 1]) this.clear();
    this.times.push(time);
    values.forEach((v, i) => {
      const s = this.series[i];
      if (s.fromFirst && Number.isNaN(this.first[i]) && Number.isFinite(v)) this.first[i] = v;
      s.values.push(s.fromFirst ? v - this.first[i] : v);
    });
    while (this.times.length > 2 && this.times[0] < time - this.windowSeconds) {
      this.times.shift();
      for (const s of this.series) s.values.shift();
    }
  }

  /** The value range a series is drawn over: its own, widened to its group's noise floor. */
  range(s: Series): [number, number] {
    const vals = s.values;
    let lo = Infinity, hi = -Infinity;
    for (const v of vals) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
    let scale = Math.max(Math.abs(lo), Math.abs(hi));
    // The group's magnitude in the core's own terms (a `fromFirst` series with its first value
    // added back: 30 J of gas is the scale its wiggles are noise against, shown from 0 or not).
    if (s.group) this.series.forEach((o, k) => {
      const at = o.fromFirst && Number.isFinite(this.first[k]) ? this.first[k] : 0;
      if (o.group === s.group) for (const v of o.values) scale = Math.max(scale, Math.abs(v + at));
    });
    const floor = Math.max(NOISE_FRACTION * scale, 1e-12);
    if (hi - lo < floor) {
      const mid = (hi + lo) / 2;
      // Never below zero for a series that is not (the kinetic energy sits on the bottom).
      const base = lo >= 0 ? Math.max(0, mid - floor / 2) : mid - floor / 2;
      return [base, base + floor];
    }
    return [lo, hi];
  }

  draw(): void {
    const { ctx, canvas } = this;
    const w = canvas.width, h = canvas.height;
    ctx.clearRect(0, 0, w, h);
    ctx.fillStyle = 'rgba(15,18,22,0.75)';
    ctx.fillRect(0, 0, w, h);
    const rows = this.series.length;
    const rh = h / rows;
    ctx.font = '10px sans-serif';
    this.series.forEach((s, r) => {
      const y0 = r * rh;
      const vals = s.values;
      if (vals.length === 0) return;
      const [lo, hi] = this.range(s);
      const top = y0 + LABEL_PX, span = rh - LABEL_PX - 3;
      ctx.strokeStyle = s.color;
      ctx.beginPath();
      // One value (the plots just restarted: a new model, or a rewind while paused): a level
      // line across, with its value, not an empty plot.
      const shownVals = vals.length === 1 ? [vals[0], vals[0]] : vals;
      shownVals.forEach((v, i) => {
        const x = (i / (shownVals.length - 1)) * (w - 4) + 2;
        const y = top + span - ((v - lo) / (hi - lo)) * span;
        if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
      });
      ctx.stroke();
      ctx.fillStyle = s.color;
      const last = vals[vals.length - 1];
      const note = last < 0 && s.whyNegative ? `  (${s.whyNegative})` : '';
      ctx.fillText(`${s.label} ${fmt(last)}${note}`, 4, y0 + 10);
    });
  }
}

export function fmt(v: number): string {
  if (!Number.isFinite(v)) return String(v);
  const a = Math.abs(v);
  return a !== 0 && (a < 1e-3 || a >= 1e5) ? v.toExponential(2) : v.toFixed(a < 1 ? 4 : 2);
}
