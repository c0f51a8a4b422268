// Validates each glTF/GLB named on the command line with the Khronos glTF validator (pinned by
// package-lock.json) and prints one tab-separated line per file: path, error count, warning count,
// the distinct error codes (comma-separated) and the first error's message ("-" when none). For
// scripts/gltf-validate.
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

async function validate(file) {
  let bytes;
  try {
    bytes = fs.readFileSync(file);
  } catch (e) {
    return [file, 1, 0, 'IO_ERROR', String(e.message)];
  }
  try {
    const report = await validator.validateBytes(new Uint8Array(bytes), {
      uri: path.basename(file),
      maxIssues: 1000,
      externalResourceFunction: (uri) => new Promise((resolve, reject) => {
        fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)), (err, data) => {
          if (err) reject(err.toString()); else resolve(data);
        });
      }),
    });
    const errors = report.issues.messages.filter((m) => m.severity === 0);
    const first = errors[0];
    const codes = [...new Set(errors.map((m) => m.code))].join(',');
    return [file, report.issues.numErrors, report.issues.numWarnings, codes || '-',
            first ? `${first.message}${first.pointer ? ' at ' + first.pointer : ''}` : '-'];
  } catch (e) {
    return [file, 1, 0, 'UNREADABLE', String(e)];
  }
}

(async () => {
  for (const file of process.argv.slice(2)) {
    console.log((await validate(file)).map((v) => String(v).replace(/[\t\n]/g, ' ')).join('\t'));
  }
})();
