// Validates a .glb with the Khronos glTF validator; prints the issue summary and exits 1 on errors.
// Usage: node validate_gltf.js FILE.glb
'use strict';
const fs = require('fs');
const validator = require('gltf-validator');
const file = process.argv[2];
const data = new Uint8Array(fs.readFileSync(file));
validator.validateBytes(data, { maxIssues: 50 }).then((report) => {
  const i = report.issues;
  console.log(`errors ${i.numErrors} warnings ${i.numWarnings} infos ${i.numInfos} hints ${i.numHints}`);
  for (const m of i.messages.slice(0, 20)) console.log(`  [${m.severity}] ${m.code} ${m.pointer || ''}: ${m.message}`);
  process.exit(i.numErrors === 0 ? 0 : 1);
}).catch((e) => { console.error('validator failed:', e); process.exit(2); });
