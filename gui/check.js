// Lint and format check of the page code (ctest `gui_lint`): every JavaScript file must parse
// (node --check), and every page file follows the house rules below. No npm package needed.
'use strict';
const fs = require('fs');
const path = require('path');
const { execFileSync } = require('child_process');

const root = path.resolve(__dirname, '..');
const files = [];
for (const dir of ['gui/src', 'tests/gui']) {
  for (const name of fs.readdirSync(path.join(root, dir)).sort()) {
    if (/\.(js|css|html)$/.test(name)) files.push(path.join(dir, name));
  }
}
files.push('gui/check.js');

const MAX_LINE = 200;
// The only absolute URLs a page may hold: XML namespaces (no network request ever).
const ALLOWED_URL = /https?:\/\/www\.w3\.org\/2000\/svg/g;
const problems = [];
for (const rel of files) {
  const text = fs.readFileSync(path.join(root, rel), 'utf8');
  const lines = text.split('\n');
  lines.forEach((line, i) => {
    const where = `${rel}:${i + 1}`;
    if (line.includes('\t')) problems.push(`${where}: tab (indent with spaces)`);
    if (/\s+$/.test(line)) problems.push(`${where}: trailing whitespace`);
    if (line.length > MAX_LINE) problems.push(`${where}: line longer than ${MAX_LINE} characters`);
    if (/https?:\/\//.test(line.replace(ALLOWED_URL, ''))) problems.push(`${where}: absolute URL (pages work offline)`);
    if (/\bvar\s/.test(line) && rel.endsWith('.js') && !rel.endsWith('check.js')) problems.push(`${where}: var (use const or let)`);
    if (/\bconsole\.log\(/.test(line) && rel.startsWith('gui/src')) problems.push(`${where}: console.log in page code`);
  });
  if (!text.endsWith('\n')) problems.push(`${rel}: no newline at the end`);
  if (rel.endsWith('.js')) {
    if (!/^\/\/ /.test(text)) problems.push(`${rel}:1: starts without a header comment`);
    if (!text.includes("'use strict';")) problems.push(`${rel}: no 'use strict'`);
    try {
      execFileSync(process.execPath, ['--check', path.join(root, rel)], { stdio: 'pipe' });
    } catch (e) {
      problems.push(`${rel}: does not parse:\n${e.stderr}`);
    }
  }
}
if (problems.length) {
  console.error(problems.join('\n'));
  console.error(`gui lint: ${problems.length} problem(s) in ${files.length} files`);
  process.exit(1);
}
console.log(`gui lint: ${files.length} files ok`);
