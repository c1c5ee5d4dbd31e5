// SPDX-License-Identifier: GPL-3.0-or-later
// Runs delatin (Mapbox's greedy insertion) on a raw little-endian Float32 grid and prints,
// per tolerance, one JSON line: {tol, vertices, triangles, seconds, delatinMaxError,
// measuredMaxError, uncovered}. 'seconds' times run(tol) alone; measuredMaxError is
// checked again here at every cell by rasterising the final triangles, so that delatin
// is judged the same way as tinlod (which measures its own TIN independently).
// Usage: node run.mjs GRID.f32 WIDTH HEIGHT TOL [TOL ...]
import { readFileSync } from 'node:fs';
import { endianness } from 'node:os';
import Delatin from 'delatin';

const [file, w, h, ...tols] = process.argv.slice(2);
const width = Number(w), height = Number(h);
if (!file || !(width > 1) || !(height > 1) || tols.length === 0) {
    console.error('usage: node run.mjs GRID.f32 WIDTH HEIGHT TOL [TOL ...]');
    process.exit(2);
}
if (endianness() !== 'LE') throw new Error('a little-endian host is assumed');
const buf = readFileSync(file);
if (buf.length !== 4 * width * height) throw new Error(`${file}: ${buf.length} bytes, not 4 * ${width} * ${height}`);
// Copy into a fresh ArrayBuffer: a Buffer's byteOffset need not be a multiple of 4.
const data = new Float32Array(buf.buffer.slice(buf.byteOffset, buf.byteOffset + buf.length));

// Largest |TIN - DEM| over all cells, each cell taken by every closed triangle holding it
// (edges and vertices included), with barycentric interpolation in pixel coordinates.
// The coordinates are integers, so the inside test on the edge functions is exact.
function measure(coords, triangles) {
    const covered = new Uint8Array(width * height);
    let maxError = 0;
    for (let t = 0; t < triangles.length; t += 3) {
        const ax = coords[2 * triangles[t]], ay = coords[2 * triangles[t] + 1];
        const bx = coords[2 * triangles[t + 1]], by = coords[2 * triangles[t + 1] + 1];
        const cx = coords[2 * triangles[t + 2]], cy = coords[2 * triangles[t + 2] + 1];
        const area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
        if (area === 0) continue; // a degenerate triangle covers nothing of its own
        const s = Math.sign(area);
        const za = data[ay * width + ax], zb = data[by * width + bx], zc = data[cy * width + cx];
        const x0 = Math.min(ax, bx, cx), x1 = Math.max(ax, bx, cx);
        for (let y = Math.min(ay, by, cy), y1 = Math.max(ay, by, cy); y <= y1; y++) {
            for (let x = x0; x <= x1; x++) {
                const wa = (cx - bx) * (y - by) - (cy - by) * (x - bx); // weight of a
                const wb = (ax - cx) * (y - cy) - (ay - cy) * (x - cx); // weight of b
                const wc = area - wa - wb;                              // weight of c
                if (s * wa < 0 || s * wb < 0 || s * wc < 0) continue;
                const i = y * width + x;
                const e = Math.abs((wa * za + wb * zb + wc * zc) / area - data[i]);
                if (e > maxError) maxError = e;
                covered[i] = 1;
            }
        }
    }
    let uncovered = 0; // cells no triangle holds: must be 0 for the maximum to mean anything
    for (let i = 0; i < covered.length; i++) uncovered += 1 - covered[i];
    return { maxError, uncovered };
}

for (const tol of tols.map(Number)) {
    const d = new Delatin(data, width, height);
    const start = process.hrtime.bigint();
    d.run(tol);
    const seconds = Number(process.hrtime.bigint() - start) / 1e9;
    const m = measure(d.coords, d.triangles);
    console.log(JSON.stringify({
        tol, vertices: d.coords.length / 2, triangles: d.triangles.length / 3, seconds,
        delatinMaxError: d.getMaxError(), measuredMaxError: m.maxError, uncovered: m.uncovered,
    }));
}
