import { describe, expect, it } from 'vitest';
import { strokesToSvg, svgStrokes } from './strokesSvg.ts';

describe('strokes as SVG in mm', () => {
  const svg = strokesToSvg([[10, 20, 30.5, 40.25, 50, 60], [1, 2], [], [0, 0, 125, 125]], { page: [0, 0, 125, 125], title: 'as drawn <test>' });

  it('is an SVG whose user unit is the millimetre', () => {
    expect(svg).toMatch(/^<\?xml version="1.0" encoding="UTF-8"\?>\n<svg xmlns="http:\/\/www.w3.org\/2000\/svg" width="125mm" height="125mm" viewBox="0 0 125 125">/);
    expect(svg).toContain('<title>as drawn &lt;test&gt;</title>');
    expect(svg.trimEnd().endsWith('</svg>')).toBe(true);
  });

  it('writes one polyline per stroke, in order, a dot as a point twice, and skips empty strokes', () => {
    expect(svg.match(/<polyline /g)).toHaveLength(3);
    expect(svg).toContain('<polyline points="10,20 30.5,40.25 50,60"/>');
    expect(svg).toContain('<polyline points="1,2 1,2"/>');
    expect(svgStrokes(svg)).toEqual([[10, 20, 30.5, 40.25, 50, 60], [1, 2, 1, 2], [0, 0, 125, 125]]);
  });

  it('rounds to the µm and keeps negative coordinates and page offsets', () => {
    const s = strokesToSvg([[-1.23456, 0.0004, 2, 3]], { page: [-10, 5, 110, 105], title: 't', digits: 3 });
    expect(s).toContain('viewBox="-10 5 120 100"');
    expect(s).toContain('width="120mm" height="100mm"');
    expect(s).toContain('points="-1.235,0 2,3"');
  });

  it('refuses a page without area', () => {
    expect(() => strokesToSvg([], { page: [0, 0, 0, 10], title: 't' })).toThrow(/positive size/);
  });
});
