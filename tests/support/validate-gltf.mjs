#!/usr/bin/env node
// Validates a glTF 2.0 file (.gltf or .glb) with the Khronos gltf-validator installed by
// scripts/fetch-node-tools.sh into .cache/node/. Prints one line of counts, then one line per message:
//   numErrors 0 numWarnings 0 numInfos 2 numHints 0
//   info UNSUPPORTED_EXTENSION /extensionsUsed/0: Cannot validate an extension as it is not supported ...
// Exits 0 when the file has no errors, 1 when it has errors, 2 on usage errors or when the validator is not
// installed. External resources (buffers, images) are read relative to the file.
import { readFile } from 'node:fs/promises';
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const file = process.argv[2];
if (!file || process.argv.length > 3) {
  console.error('usage: validate-gltf.mjs FILE.gltf|FILE.glb');
  process.exit(2);
}
const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const require = createRequire(path.join(root, '.cache', 'node', 'package.json'));
let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.error('validate-gltf: gltf-validator is not installed; run scripts/fetch-node-tools.sh');
  process.exit(2);
}
const severities = ['error', 'warning', 'info', 'hint'];
try {
  const bytes = await readFile(file);
  const report = await validator.validateBytes(new Uint8Array(bytes), {
    uri: path.basename(file),
    maxIssues: 1000,
    externalResourceFunction: (uri) =>
      readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
  });
  const issues = report.issues;
  console.log(`numErrors ${issues.numErrors} numWarnings ${issues.numWarnings} numInfos ${issues.numInfos} ` +
              `numHints ${issues.numHints}`);
  for (const m of issues.messages) {
    console.log(`${severities[m.severity] ?? m.severity} ${m.code} ${m.pointer ?? ''}: ${m.message}`);
  }
  process.exit(issues.numErrors > 0 ? 1 : 0);
} catch (e) {
  console.error(`validate-gltf: ${file}: ${e.message ?? e}`);
  process.exit(1);
}
