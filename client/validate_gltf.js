#!/usr/bin/env node
// Runs the Khronos glTF validator (npm gltf-validator, pinned in package-lock.json) on one
// .gltf/.glb file, its buffers and images read from beside it, and prints the issues as JSON:
//   {"file", "validator", "errors": [...], "warnings": [...], "infos": [...], "hints": [...]}
// each issue {code, message, pointer}. Exit status: 0 when the validator ran (whatever it
// found), 2 when it could not (no file, unreadable, not glTF).
//
//   node client/validate_gltf.js out/scene.gltf
'use strict';

const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

const severities = ['errors', 'warnings', 'infos', 'hints'];

async function validate(file) {
    const bytes = new Uint8Array(fs.readFileSync(file));
    const report = await validator.validateBytes(bytes, {
        uri: path.basename(file),
        maxIssues: 0, // all of them
        externalResourceFunction: (uri) =>
            fs.promises.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)))
                .then((data) => new Uint8Array(data)),
    });
    const out = {file, validator: validator.version()};
    for (const s of severities) out[s] = [];
    for (const m of report.issues.messages)
        out[severities[m.severity]].push({code: m.code, message: m.message, pointer: m.pointer});
    return out;
}

if (process.argv.length !== 3) {
    console.error('usage: node validate_gltf.js FILE.gltf');
    process.exit(2);
}
validate(process.argv[2]).then(
    (out) => console.log(JSON.stringify(out, null, 2)),
    (error) => {
        console.error(`validate_gltf: ${error}`);
        process.exit(2);
    });
