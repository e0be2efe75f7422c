// Bundles the page script (src/viewer.js and three.js from node_modules) with esbuild and writes it
// as a C++ source for the view command to embed in every page. Chunks of raw string literals keep
// each literal far below the length a compiler must support (-Woverlength-strings).
//   node bundle_script.mjs OUTPUT.cc
import { writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { build } from 'esbuild';

const output = process.argv[2];
const input = join(dirname(fileURLToPath(import.meta.url)), 'src', 'viewer.js');
const result = await build({
  entryPoints: [input], bundle: true, format: 'iife', minify: true, charset: 'ascii', write: false,
  logLevel: 'warning',
});
const js = result.outputFiles[0].text;
// The page inlines the script: it must not end its own <script> element (esbuild escapes that in strings).
if (/<\/script/i.test(js)) throw new Error('the bundled script contains "</script"');
const delimiter = 'sp_js';
if (js.includes(`)${delimiter}"`)) throw new Error(`${input} contains the raw string delimiter ${delimiter}`);
const chunkSize = 16000;
const chunks = [];
for (let i = 0; i < js.length; i += chunkSize) chunks.push(`R"${delimiter}(${js.slice(i, i + chunkSize)})${delimiter}"`);
writeFileSync(output, `// Generated at build time by stairplan/viewer/bundle_script.mjs; do not edit.
#include "stairplan/viewer/viewer_bundle.h"

namespace stairplan {
namespace {
const char* const kChunks[] = {
${chunks.join(',\n')}
};
}  // namespace

const std::string& ViewerBundleJs() {
  static const std::string bundle = [] {
    std::string all;
    for (const char* chunk : kChunks) all += chunk;
    return all;
  }();
  return bundle;
}

}  // namespace stairplan
`);
