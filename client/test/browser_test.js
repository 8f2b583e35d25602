#!/usr/bin/env node
// The browser client's test (issue #29; ctest `browser_client`, label browser): bakes a scene's
// lightmaps, serves them with `penumbra serve`, opens the page in headless Chromium (Debian's
// /usr/bin/chromium, driven by playwright-core, WebGL 2 from ANGLE on SwiftShader) and checks:
//   1. the page loads, and its screenshot against preview.png: mean absolute difference
//      <= 2/255 and 99th percentile <= 8/255 (image_difference.js); a drag on the canvas then
//      turns the view (orbit controls);
//   2. with lightmap_0.png flipped upside down the same comparison fails;
//   3. without scene.gltf, without lightmap_0.png, or without a WebGL 2 context the page shows
//      an error naming what is missing (in the DOM, the canvas hidden).
// Any failure, a missing browser or WebGL among them, exits 1.
//
//   node client/test/browser_test.js --penumbra build/penumbra --scene data/cornell/scene.json \
//       --work build/browser_test [--bake-flags "--atlas 256 --texels-per-metre 100 ..."]
'use strict';

const {spawn, spawnSync} = require('child_process');
const fs = require('fs');
const path = require('path');
const {PNG} = require('pngjs');
const {chromium} = require('playwright-core');
const {readPng, imageDifference} = require('./image_difference.js');

const CHROMIUM = '/usr/bin/chromium';
// Software WebGL: ANGLE on SwiftShader, also where the machine has no GPU or display.
const CHROMIUM_ARGS = ['--use-angle=swiftshader', '--enable-unsafe-swiftshader',
                       '--force-color-profile=srgb'];
const MAX_MEAN = 2 / 255, MAX_P99 = 8 / 255;
const PAGE_TIMEOUT_MS = 30000;

const results = [];
let lastCheck = Date.now();
function check(name, ok, detail) {
    results.push({name, ok});
    const seconds = ((Date.now() - lastCheck) / 1000).toFixed(1);
    lastCheck = Date.now();
    console.log(`${ok ? 'PASS' : 'FAIL'} ${name} (${seconds} s): ${detail}`);
}

function parseArgs(argv) {
    // A coarse solve (the comparison does not depend on its accuracy) keeps the bake near 5 s.
    const args = {bakeFlags: '--atlas 256 --texels-per-metre 100 --max-edge 0.2 --epsilon 0.01'};
    for (let i = 2; i + 1 < argv.length; i += 2) {
        const key = argv[i].replace(/^--/, '').replace(/-(.)/g, (_, c) => c.toUpperCase());
        args[key] = argv[i + 1];
    }
    for (const key of ['penumbra', 'scene', 'work'])
        if (!args[key]) throw new Error(`missing --${key} (see the file's header)`);
    return args;
}

function bake(args, out) {
    const flags = ['lightmap', args.scene, '-o', out, '-q', ...args.bakeFlags.split(/\s+/)];
    const run = spawnSync(args.penumbra, flags, {encoding: 'utf8'});
    if (run.status !== 0)
        throw new Error(`penumbra ${flags.join(' ')}: exit ${run.status}: ${run.stderr}`);
}

// Copies of the bake with one thing broken, beside it under work/.
function makeVariants(work) {
    const good = path.join(work, 'bake');
    const variant = (name, change) => {
        const dir = path.join(work, name);
        fs.cpSync(good, dir, {recursive: true});
        change(dir);
    };
    variant('flipped', (dir) => {
        const file = path.join(dir, 'lightmap_0.png');
        const png = PNG.sync.read(fs.readFileSync(file));
        const row = 4 * png.width, flipped = Buffer.alloc(png.data.length);
        for (let y = 0; y < png.height; ++y)
            png.data.copy(flipped, (png.height - 1 - y) * row, y * row, (y + 1) * row);
        png.data = flipped;
        fs.writeFileSync(file, PNG.sync.write(png));
    });
    variant('no_gltf', (dir) => fs.rmSync(path.join(dir, 'scene.gltf')));
    variant('no_atlas', (dir) => fs.rmSync(path.join(dir, 'lightmap_0.png')));
}

// `penumbra serve work --port 0`, resolved with its port once it listens.
function startServer(args, root) {
    const server = spawn(args.penumbra, ['serve', root, '--port', '0', '-q'],
                         {stdio: ['ignore', 'pipe', 'inherit']});
    process.on('exit', () => server.kill()); // also when the test ends by an error
    return new Promise((resolve, reject) => {
        let out = '';
        server.stdout.on('data', (chunk) => {
            out += chunk;
            const match = out.match(/http:\/\/127\.0\.0\.1:(\d+)\//);
            if (match) resolve({server, port: Number(match[1])});
        });
        server.on('exit', (code) => reject(new Error(`penumbra serve exited with ${code}`)));
    });
}

// Opens the page for one glTF; resolves with the page's state and status line.
async function openPage(context, url, size, {noWebgl = false} = {}) {
    const page = await context.newPage();
    await page.setViewportSize(size);
    if (noWebgl)
        await page.addInitScript(() => {
            const getContext = HTMLCanvasElement.prototype.getContext;
            HTMLCanvasElement.prototype.getContext = function(type, ...rest) {
                return /webgl/.test(type) ? null : getContext.call(this, type, ...rest);
            };
        });
    page.on('pageerror', (error) => console.log(`page error: ${error.message}`));
    await page.goto(url);
    await page.waitForFunction(() => document.body.dataset.state !== 'loading', null,
                               {timeout: PAGE_TIMEOUT_MS});
    const state = await page.evaluate(() => document.body.dataset.state);
    const status = await page.evaluate(() => document.getElementById('status').textContent);
    const statusVisible = await page.locator('#status').isVisible();
    const canvasVisible = await page.locator('canvas').isVisible();
    return {page, state, status, statusVisible, canvasVisible};
}

async function webglRenderer(page) {
    return page.evaluate(() => {
        const gl = document.createElement('canvas').getContext('webgl2');
        if (!gl) return 'none';
        const info = gl.getExtension('WEBGL_debug_renderer_info');
        return gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER);
    });
}

// The page's screenshot against preview.png.
async function compareWithPreview(context, base, work, gltf, shot) {
    const preview = readPng(path.join(work, 'bake', 'preview.png'));
    const size = {width: preview.width, height: preview.height};
    const view = await openPage(context, `${base}/?gltf=${gltf}`, size);
    if (view.state !== 'loaded') {
        await view.page.close();
        return {loaded: false, status: view.status};
    }
    const canvas = view.page.locator('canvas');
    await canvas.screenshot({path: shot});
    const renderer = await webglRenderer(view.page);
    // A drag turns the view about the orbit's centre: the picture changes.
    const box = await canvas.boundingBox();
    const [x, y] = [box.x + box.width / 2, box.y + box.height / 2];
    await view.page.mouse.move(x, y);
    await view.page.mouse.down();
    await view.page.mouse.move(x + box.width / 8, y, {steps: 4});
    await view.page.mouse.up();
    const turned = PNG.sync.read(await canvas.screenshot());
    await view.page.close();
    return {loaded: true, renderer, turned: imageDifference(preview, turned),
            ...imageDifference(preview, readPng(shot))};
}

const fmt = (d) => `mean ${(255 * d.mean).toFixed(3)}/255, 99th percentile ${255 * d.p99}/255`;

async function checkPreview(context, base, work) {
    const good = await compareWithPreview(context, base, work, 'bake/scene.gltf',
                                          path.join(work, 'screenshot.png'));
    if (!good.loaded) return check('page matches preview.png', false, good.status);
    console.log(`WebGL renderer: ${good.renderer}`);
    check('page matches preview.png', good.mean <= MAX_MEAN && good.p99 <= MAX_P99, fmt(good));
    check('orbit controls turn the view', good.turned.mean > MAX_MEAN,
          `after a drag of 1/8 of the width: ${fmt(good.turned)}`);
    const flipped = await compareWithPreview(context, base, work, 'flipped/scene.gltf',
                                             path.join(work, 'screenshot_flipped.png'));
    check('a flipped atlas fails the comparison',
          flipped.loaded && !(flipped.mean <= MAX_MEAN && flipped.p99 <= MAX_P99),
          flipped.loaded ? fmt(flipped) : flipped.status);
}

async function checkError(context, base, name, gltf, expected, options) {
    const view = await openPage(context, `${base}/?gltf=${gltf}`, {width: 256, height: 256},
                                options);
    await view.page.close();
    check(name,
          view.state === 'error' && view.status.includes(expected) && view.statusVisible &&
              !view.canvasVisible,
          `state ${view.state}, "${view.status}"`);
}

async function main() {
    const started = Date.now();
    const args = parseArgs(process.argv);
    if (!fs.existsSync(CHROMIUM))
        throw new Error(`${CHROMIUM} is missing: run scripts/setup.sh --deps (Debian's chromium)`);
    fs.rmSync(args.work, {recursive: true, force: true});
    fs.mkdirSync(args.work, {recursive: true});
    bake(args, path.join(args.work, 'bake'));
    const baked = Date.now();
    makeVariants(args.work);
    const {server, port} = await startServer(args, args.work);
    const browser = await chromium.launch({executablePath: CHROMIUM, args: CHROMIUM_ARGS});
    // One context for every page: three.js's modules are parsed once.
    const context = await browser.newContext({deviceScaleFactor: 1});
    console.log(`Chromium ${browser.version()} started in ${((Date.now() - baked) / 1000).toFixed(1)} s`);
    lastCheck = Date.now();
    try {
        const base = `http://127.0.0.1:${port}`;
        await checkPreview(context, base, args.work);
        await checkError(context, base, 'missing glTF is an error', 'no_gltf/scene.gltf',
                         'scene.gltf');
        await checkError(context, base, 'missing atlas is an error', 'no_atlas/scene.gltf',
                         'lightmap_0.png');
        await checkError(context, base, 'no WebGL is an error', 'bake/scene.gltf', 'WebGL',
                         {noWebgl: true});
    } finally {
        await browser.close();
        server.kill();
    }
    const failed = results.filter((r) => !r.ok).length;
    console.log(`bake ${((baked - started) / 1000).toFixed(1)} s, browser ` +
                `${((Date.now() - baked) / 1000).toFixed(1)} s`);
    console.log(failed === 0 ? `browser_test: all ${results.length} checks passed`
                             : `browser_test: ${failed} of ${results.length} checks failed`);
    return failed === 0 ? 0 : 1;
}

main().then((code) => process.exit(code), (error) => {
    console.error(`browser_test: ${error.message ?? error}`);
    process.exit(1);
});
