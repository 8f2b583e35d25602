// The difference of two 8-bit PNG pictures of the same size, as the browser test measures it:
// per pixel and channel (R, G, B; alpha ignored) the absolute difference of the 8-bit values,
// divided by 255; their mean and their 99th percentile (nearest rank).
'use strict';

const fs = require('fs');
const {PNG} = require('pngjs');

function readPng(file) {
    return PNG.sync.read(fs.readFileSync(file));
}

function imageDifference(a, b) {
    if (a.width !== b.width || a.height !== b.height)
        throw new Error(`sizes differ: ${a.width}x${a.height} and ${b.width}x${b.height}`);
    const counts = new Array(256).fill(0);
    let sum = 0;
    for (let p = 0; p < a.width * a.height; ++p)
        for (let c = 0; c < 3; ++c) {
            const d = Math.abs(a.data[4 * p + c] - b.data[4 * p + c]);
            counts[d] += 1;
            sum += d;
        }
    const n = 3 * a.width * a.height;
    const rank = Math.ceil(0.99 * n);
    let seen = 0, p99 = 0;
    while (seen + counts[p99] < rank) seen += counts[p99++];
    return {mean: sum / n / 255, p99: p99 / 255, max: counts.findLastIndex((k) => k > 0) / 255};
}

module.exports = {readPng, imageDifference};
