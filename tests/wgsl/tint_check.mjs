// Compiles one WGSL file with Tint, Dawn's WGSL compiler, through the `webgpu` package's null
// backend (no GPU needed): the file must parse, resolve and validate as a shader module, and its
// `main` entry point must make a compute pipeline. Prints Tint's messages as
// FILE:LINE:COLUMN: TYPE: TEXT, then "FILE: ok" or exits 1; exits 2 on a wrong command line.
//   node tint_check.mjs FILE.wgsl
// One file per process: in this sandbox dawn.node aborts after a few dozen modules in one process
// ("The futex facility returned an unexpected error code"), and one file takes about 0.1 s.
import { create, globals } from 'webgpu';
import { readFileSync } from 'node:fs';

if (process.argv.length !== 3) {
  console.error('usage: node tint_check.mjs FILE.wgsl');
  process.exit(2);
}
const file = process.argv[2];
const code = readFileSync(file, 'utf8');
Object.assign(globalThis, globals);
const adapter = await create(['backend=null']).requestAdapter();
if (!adapter) {
  console.error('tint_check: Dawn offers no null-backend adapter');
  process.exit(1);
}
const device = await adapter.requestDevice();

device.pushErrorScope('validation');
const module = device.createShaderModule({ code });
const info = await module.getCompilationInfo();
let failed = false;
for (const m of info.messages) {
  console.log(`${file}:${m.lineNum}:${m.linePos}: ${m.type}: ${m.message}`);
  if (m.type === 'error') failed = true;
}
const moduleError = await device.popErrorScope();
if (moduleError && !failed) console.log(`${file}: error: ${moduleError.message}`);
if (!moduleError) {
  device.pushErrorScope('validation');
  device.createComputePipeline({ layout: 'auto', compute: { module, entryPoint: 'main' } });
  const pipelineError = await device.popErrorScope();
  if (pipelineError) console.log(`${file}: error: ${pipelineError.message}`);
  failed = failed || pipelineError !== null;
} else {
  failed = true;
}
if (!failed) console.log(`${file}: ok`);
process.exit(failed ? 1 : 0);
