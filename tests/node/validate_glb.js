// Validates .glb files with the Khronos glTF validator (npm gltf-validator,
// installed by scripts/node.sh) for tests/cad_document.rs.
// Usage: node validate_glb.js NODE_DIR FILE.glb...  Prints one JSON line per
// file: {"file", "errors", "warnings", "infos", "messages": [first 20 issues]};
// exits 1 when a file has an error or cannot be read.
"use strict";
const fs = require("fs");
const path = require("path");

const [dir, ...files] = process.argv.slice(2);
const validator = require(path.join(dir, "node_modules", "gltf-validator"));

async function main() {
  let failed = false;
  for (const file of files) {
    try {
      const bytes = new Uint8Array(fs.readFileSync(file));
      const report = await validator.validateBytes(bytes, {
        uri: path.basename(file),
        maxIssues: 0,
        externalResourceFunction: () => Promise.reject(new Error("no external resources")),
      });
      const i = report.issues;
      console.log(JSON.stringify({
        file,
        errors: i.numErrors,
        warnings: i.numWarnings,
        infos: i.numInfos,
        messages: i.messages.slice(0, 20),
      }));
      if (i.numErrors > 0) failed = true;
    } catch (e) {
      console.log(JSON.stringify({ file, error: String(e) }));
      failed = true;
    }
  }
  process.exit(failed ? 1 : 0);
}

main();
