// The load order of the page scripts (gui/assets.cmake joins the parts of gui/src/<script>/ in a
// fixed order): every name a part takes from a namespace while it loads (`const { a, b } = kimp;`,
// `kimp.a` outside the part's inner functions) was exported (`Object.assign(kimp, { a })`,
// `kimp.a = ...`) by an earlier part or script; a name looked up inside a function, when it runs,
// is exported by some part; a name is exported once. Run by ctest `gui_page_script_order` with the order of
// gui/assets.cmake:
//   node page_script_order.mjs ROOT kimp=core,charts,... gui=core,form,...
//   node page_script_order.mjs --self-test     (the checker finds each kind of violation)
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const acornPath = path.resolve(path.dirname(new URL(import.meta.url).pathname), '../../gui/node_modules/acorn');
const acorn = require(acornPath);

/** Every node of an AST, with the number of functions around it. */
function walk(node, visit, depth = 0) {
  if (!node || typeof node.type !== 'string') return;
  visit(node, depth);
  const inner = /Function/.test(node.type) ? depth + 1 : depth;
  for (const key of Object.keys(node)) {
    const value = node[key];
    if (Array.isArray(value)) for (const v of value) walk(v, visit, inner);
    else if (value && typeof value === 'object' && key !== 'loc') walk(value, visit, inner);
  }
}

function propertyName(p) {
  if (p.computed) return null;
  return p.key.type === 'Identifier' ? p.key.name : p.key.value;
}

/** The namespace a part declares (`const kimp = {};`), its imports and its exports. */
function analyse(source, file, namespaces) {
  const ast = acorn.parse(source, { ecmaVersion: 'latest', sourceType: 'script', locations: true });
  const out = { declares: null, imports: [], exports: [] };
  walk(ast, (node, depth) => {
    if (node.type === 'VariableDeclarator' && node.init) {
      if (node.id.type === 'Identifier' && node.init.type === 'ObjectExpression' && namespaces.has(node.id.name))
        out.declares = node.id.name;
      if (node.id.type === 'ObjectPattern' && node.init.type === 'Identifier' && namespaces.has(node.init.name))
        for (const p of node.id.properties)
          if (p.type === 'Property')
            out.imports.push({ ns: node.init.name, name: propertyName(p), line: p.loc.start.line, depth });
    }
    if (
      node.type === 'CallExpression' &&
      node.callee.type === 'MemberExpression' &&
      node.callee.object.name === 'Object' &&
      node.callee.property.name === 'assign' &&
      node.arguments[0]?.type === 'Identifier' &&
      namespaces.has(node.arguments[0].name) &&
      node.arguments[1]?.type === 'ObjectExpression'
    )
      for (const p of node.arguments[1].properties)
        out.exports.push({ ns: node.arguments[0].name, name: propertyName(p), line: p.loc.start.line });
    if (node.type === 'AssignmentExpression' && node.left.type === 'MemberExpression') {
      const m = node.left;
      if (m.object.type === 'Identifier' && namespaces.has(m.object.name) && !m.computed)
        out.exports.push({ ns: m.object.name, name: m.property.name, line: m.loc.start.line, assigned: m });
    }
  });
  // Reads `ns.name` that are not the left side of an export.
  const assigned = new Set(out.exports.map((e) => e.assigned).filter(Boolean));
  walk(ast, (node, depth) => {
    if (
      node.type === 'MemberExpression' &&
      !node.computed &&
      node.object.type === 'Identifier' &&
      namespaces.has(node.object.name) &&
      !assigned.has(node)
    )
      out.imports.push({ ns: node.object.name, name: node.property.name, line: node.loc.start.line, depth });
  });
  for (const e of out.exports) delete e.assigned;
  out.file = file;
  return out;
}

/**
 * The violations of the page scripts `scripts` = [{name, parts: [{file, source}]}], loaded in this
 * order: each script's first part declares its namespace.
 */
export function check(scripts) {
  const errors = [];
  const namespaces = new Set();
  for (const s of scripts) {
    const first = s.parts[0];
    const m = /^const (\w+) = \{\};/m.exec(first.source);
    if (!m) errors.push(`${first.file}: the first part of ${s.name}.js declares no namespace (const NAME = {};)`);
    else namespaces.add(m[1]);
  }
  const parts = scripts.flatMap((s) => s.parts).map((part) => analyse(part.source, part.file, namespaces));
  const anywhere = new Set(parts.flatMap((a) => a.exports.map((e) => `${e.ns}.${e.name}`)));
  const exported = new Map(); // "ns.name" -> file of an earlier part that exported it
  for (const a of parts) {
      const own = new Set(a.exports.map((e) => `${e.ns}.${e.name}`));
      for (const i of a.imports) {
        const key = `${i.ns}.${i.name}`;
        // Depth > 1: inside a function of the part's IIFE, looked up when it runs.
        const lateBound = i.depth > 1;
        if (exported.has(key) || own.has(key) || (lateBound && anywhere.has(key))) continue;
        errors.push(`${a.file}:${i.line}: uses ${key}, which ` +
                    (lateBound ? 'no part exports' : 'no earlier part exports'));
      }
      for (const e of a.exports) {
        const key = `${e.ns}.${e.name}`;
        if (exported.has(key))
          errors.push(`${a.file}:${e.line}: exports ${key} again (first by ${exported.get(key)})`);
        else exported.set(key, a.file);
      }
  }
  return errors;
}

function selfTest() {
  const core = { file: 'core.js', source: "const ns = {};\n(function () {\n  Object.assign(ns, { a });\n})();\n" };
  const cases = [
    ['a correct order', [core, { file: 'b.js', source: 'const { a } = ns;\nns.b = a;\n' }], 0],
    ['a name exported by a later part', [core, { file: 'b.js', source: 'const { c } = ns;\n' },
      { file: 'c.js', source: 'Object.assign(ns, { c: 1 });\n' }], 1],
    ['a name used through the namespace and never exported', [core, { file: 'b.js', source: 'f(ns.zz);\n' }], 1],
    ['a name looked up when a function runs, exported later',
      [core, { file: 'b.js', source: '(function () {\n  function g() { return ns.c; }\n})();\n' },
        { file: 'c.js', source: 'Object.assign(ns, { c: 1 });\n' }], 0],
    ['a name looked up when a function runs, never exported',
      [core, { file: 'b.js', source: '(function () {\n  function g() { return ns.zz; }\n})();\n' }], 1],
    ['a name exported twice', [core, { file: 'b.js', source: 'Object.assign(ns, { a: 2 });\n' }], 1],
  ];
  let failed = 0;
  for (const [what, parts, expected] of cases) {
    const errors = check([{ name: 'page', parts }]);
    const ok = errors.length === expected;
    console.log(`${ok ? 'ok' : 'FAILED'}: ${what}: ${errors.length} violation(s) ${errors.join('; ')}`);
    if (!ok) ++failed;
  }
  return failed;
}

function main(argv) {
  if (argv[0] === '--self-test') return selfTest() ? 1 : 0;
  const root = argv[0];
  const scripts = argv.slice(1).map((arg) => {
    const [name, list] = arg.split('=');
    return {
      name,
      parts: list.split(',').map((part) => {
        const file = path.join('gui/src', name, `${part}.js`);
        return { file, source: fs.readFileSync(path.join(root, file), 'utf8') };
      }),
    };
  });
  const errors = check(scripts);
  for (const e of errors) console.log(`error: ${e}`);
  const n = scripts.reduce((sum, s) => sum + s.parts.length, 0);
  console.log(`${scripts.length} page scripts, ${n} parts: ${errors.length} load-order violation(s)`);
  return errors.length ? 1 : 0;
}

process.exitCode = main(process.argv.slice(2));
