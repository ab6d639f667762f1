// SPDX-License-Identifier: MIT
// Runs the Khronos glTF Validator (tests/npm, installed by `.ci/deps test`)
// on each file named, its .bin and images read from beside it. Prints each
// file's errors and warnings; exits 1 if any file has an error.
// Usage: node gltf_validate.js FILE...
"use strict";
const fs = require("fs");
const path = require("path");
const validator = require(path.join(__dirname, "npm", "node_modules", "gltf-validator"));

async function validate(file) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
        uri: path.basename(file),
        maxIssues: 50,
        externalResourceFunction: (uri) =>
            new Promise((resolve, reject) => {
                fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)), (err, data) =>
                    err ? reject(err.toString()) : resolve(new Uint8Array(data)));
            }),
    });
    const issues = report.issues;
    for (const m of issues.messages)
        if (m.severity <= 1) console.log(`${file}: ${m.severity === 0 ? "error" : "warning"} ${m.code}: ${m.message} (${m.pointer || ""})`);
    console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings`);
    return issues.numErrors;
}

(async () => {
    let errors = 0;
    for (const file of process.argv.slice(2)) errors += await validate(file);
    process.exit(errors ? 1 : 0);
})().catch((e) => {
    console.error(e);
    process.exit(2);
});
