// Runs the Khronos glTF validator (npm gltf-validator, installed by
// scripts/install-deps.sh into .cache/npm) on a .glb: prints its issue counts and the
// messages, exits 1 when there is any error or warning, 2 when it cannot run.
// Usage: node validate_gltf.js MODULE_DIR FILE.glb
const fs = require('fs');
let validator;
try {
    validator = require(process.argv[2] + '/node_modules/gltf-validator');
} catch (e) {
    console.error('validate_gltf: the glTF validator is not installed: ' + e.message);
    process.exit(2);
}
const data = new Uint8Array(fs.readFileSync(process.argv[3]));
validator.validateBytes(data, {maxIssues: 50}).then((report) => {
    const i = report.issues;
    console.log(`errors=${i.numErrors} warnings=${i.numWarnings} infos=${i.numInfos} hints=${i.numHints}`);
    for (const m of i.messages) console.log(`${m.code} ${m.severity} ${m.pointer || ''} ${m.message}`);
    process.exit(i.numErrors + i.numWarnings > 0 ? 1 : 0);
}).catch((e) => {
    console.error('validate_gltf: ' + e);
    process.exit(2);
});
