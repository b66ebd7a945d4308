// Validates a .glb/.gltf with the Khronos glTF Validator. Prints one line
// "errors=N warnings=N" and the error messages; exits 0 when there are no errors, 1 otherwise.
import { readFileSync } from "node:fs";
import { dirname, join } from "node:path";
import validator from "gltf-validator";

const file = process.argv[2];
const data = new Uint8Array(readFileSync(file));
const report = await validator.validateBytes(data, {
  uri: file,
  maxIssues: 100,
  externalResourceFunction: (uri) =>
    Promise.resolve(new Uint8Array(readFileSync(join(dirname(file), decodeURIComponent(uri))))),
});
const s = report.issues;
console.log(`errors=${s.numErrors} warnings=${s.numWarnings}`);
for (const m of s.messages) if (m.severity === 0) console.log(`${m.code}: ${m.message} (${m.pointer ?? ""})`);
process.exit(s.numErrors === 0 ? 0 : 1);
