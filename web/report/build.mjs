// Bundles src/main.js with three.js and uPlot (and uPlot's stylesheet, as text) into one script
// that `biped run` embeds in report.html. Usage: node build.mjs OUTFILE
import * as esbuild from 'esbuild';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const outfile = process.argv[2];
if (!outfile) {
  console.error('usage: node build.mjs OUTFILE');
  process.exit(2);
}
const here = path.dirname(fileURLToPath(import.meta.url));
// The libraries' MIT licenses ask for their notices in every copy: at the top of the bundle.
const notices = ['three', 'uplot'].map((name) =>
  `${name}:\n${fs.readFileSync(path.join(here, 'node_modules', name, 'LICENSE'), 'utf8').trim()}`);
await esbuild.build({
  entryPoints: [path.join(here, 'src', 'main.js')],
  outfile,
  bundle: true,
  minify: true,
  format: 'iife',
  target: 'es2020',
  loader: { '.css': 'text' },
  legalComments: 'eof',
  banner: { js: `/*! Bundled libraries and their licenses.\n\n${notices.join('\n\n')}\n*/` },
  logLevel: 'warning',
});
