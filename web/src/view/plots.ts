// Live plots of volume, pressure and energies over the last seconds, on a small 2D canvas.

export interface Series {
  label: string;
  color: string;
  values: number[];
}

export class Plots {
  private readonly ctx: CanvasRenderingContext2D;
  readonly series: Series[] = [
    { label: 'volume m³', color: '#7fd1ff', values: [] },
    { label: 'pressure Pa', color: '#ffd27f', values: [] },
    { label: 'kinetic J', color: '#ff8f8f', values: [] },
    { label: 'elastic J', color: '#9dff8f', values: [] },
    { label: 'gas J', color: '#d59dff', values: [] },
  ];
  private times: number[] = [];

  constructor(readonly canvas: HTMLCanvasElement, private readonly windowSeconds = 10) {
    this.ctx = canvas.getContext('2d')!;
  }

  clear(): void {
    this.times = [];
    for (const s of this.series) s.values = [];
  }

  push(time: number, values: number[]): void {
    if (this.times.length && time < this.times[this.times.length - 1]) this.clear();
    this.times.push(time);
    values.forEach((v, i) => this.series[i].values.push(v));
    while (this.times.length > 2 && this.times[0] < time - this.windowSeconds) {
      this.times.shift();
      for (const s of this.series) s.values.shift();
    }
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
      if (vals.length < 2) return;
      let lo = Math.min(...vals), hi = Math.max(...vals);
      if (hi - lo < 1e-12 * Math.max(1, Math.abs(hi))) { lo -= 0.5; hi += 0.5; }
      ctx.strokeStyle = s.color;
      ctx.beginPath();
      vals.forEach((v, i) => {
        const x = (i / (vals.length - 1)) * (w - 4) + 2;
        const y = y0 + rh - 3 - ((v - lo) / (hi - lo)) * (rh - 6);
        if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
      });
      ctx.stroke();
      ctx.fillStyle = s.color;
      ctx.fillText(`${s.label} ${fmt(vals[vals.length - 1])}`, 4, y0 + 11);
    });
  }
}

export function fmt(v: number): string {
  if (!Number.isFinite(v)) return String(v);
  const a = Math.abs(v);
  return a !== 0 && (a < 1e-3 || a >= 1e5) ? v.toExponential(2) : v.toFixed(a < 1 ? 4 : 2);
}
