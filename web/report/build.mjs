// Bundles src/main.js with three.js and uPlot (and uPlot's stylesheet, as text) into one script
// that `biped run` embeds in report.html. Usage: node build.mjs OUTFILE
import * as esbuild from 'esbuild';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const outfile = process.argv[2];
if (!outfile) {
  console.error('usage: node build.mjs OUTFILE');
  process.exit(2);
}
const here = path.dirname(fileURLToPath(import.meta.url));
await esbuild.build({
  entryPoints: [path.join(here, 'src', 'main.js')],
  outfile,
  bundle: true,
  minify: true,
  format: 'iife',
  target: 'es2020',
  loader: { '.css': 'text' },
  legalComments: 'eof',
  logLevel: 'warning',
});
