// Validates a glTF or GLB file with the Khronos glTF validator and prints its report's
// issues as JSON: {"numErrors": N, "numWarnings": N, "messages": [...]}.
// Usage: node gltf_validate.cjs FILE
const fs = require('fs');
const validator = require('gltf-validator');

validator
  .validateBytes(new Uint8Array(fs.readFileSync(process.argv[2])), { maxIssues: 50 })
  .then((report) => {
    const issues = report.issues;
    const messages = issues.messages.map((m) => `${m.severity} ${m.code} ${m.pointer || ''}: ${m.message}`);
    console.log(JSON.stringify({ numErrors: issues.numErrors, numWarnings: issues.numWarnings, messages }));
  })
  .catch((error) => {
    console.error(String(error));
    process.exit(1);
  });
