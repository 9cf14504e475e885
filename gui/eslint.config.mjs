// ESLint flat config of the page code, run from the repository root (ctest gui_lint):
//   gui/node_modules/.bin/eslint -c gui/eslint.config.mjs gui/src tests/gui gui/eslint.config.mjs
// JavaScript of gui/src (browser scripts) and tests/gui (node), the stylesheet and the two HTML
// pages. Lines <= 120 characters; pages work offline: no absolute URL but the SVG namespace.
import js from '@eslint/js';
import css from '@eslint/css';
import html from '@html-eslint/eslint-plugin';
import stylistic from '@stylistic/eslint-plugin';
import globals from 'globals';

const OFFLINE = {
  selector: 'Literal[value=/https?:\\/\\/(?!www\\.w3\\.org\\/2000\\/svg)/], ' +
    'TemplateElement[value.raw=/https?:\\/\\/(?!www\\.w3\\.org\\/2000\\/svg)/]',
  message: 'absolute URL: the pages work offline (no CDN, no network request)',
};

const style = {
  '@stylistic/max-len': ['error', { code: 120, ignoreUrls: false, ignoreRegExpLiterals: true }],
  '@stylistic/no-tabs': 'error',
  '@stylistic/no-trailing-spaces': 'error',
  '@stylistic/eol-last': 'error',
  '@stylistic/semi': ['error', 'always'],
  '@stylistic/quotes': ['error', 'single', { avoidEscape: true, allowTemplateLiterals: 'always' }],
  '@stylistic/comma-dangle': ['error', 'always-multiline'],
  'no-var': 'error',
  'prefer-const': 'error',
  eqeqeq: ['error', 'always'],
  strict: ['error', 'global'],
  'no-unused-vars': ['error', { args: 'none' }],
  'no-redeclare': ['error', { builtinGlobals: false }],
  'no-restricted-syntax': ['error', OFFLINE],
};

// Paths are relative to the repository (the page code and its browser tests).
export default [
  { ignores: ['gui/node_modules/**'] },
  {
    files: ['gui/src/**/*.js'],
    ...js.configs.recommended,
    plugins: { '@stylistic': stylistic },
    languageOptions: {
      ecmaVersion: 2022,
      sourceType: 'script',
      globals: { ...globals.browser, uPlot: 'readonly', kimp: 'writable', kimpGui: 'writable', jsyaml: 'readonly' },
    },
    rules: { ...js.configs.recommended.rules, ...style, 'no-console': 'error' },
  },
  {
    files: ['tests/gui/**/*.js'],
    ...js.configs.recommended,
    plugins: { '@stylistic': stylistic },
    languageOptions: { ecmaVersion: 2022, sourceType: 'commonjs', globals: { ...globals.node, ...globals.browser } },
    rules: { ...js.configs.recommended.rules, ...style },
  },
  {
    files: ['gui/eslint.config.mjs'],
    plugins: { '@stylistic': stylistic },
    languageOptions: { ecmaVersion: 2022, sourceType: 'module' },
    rules: { ...js.configs.recommended.rules, ...style, strict: 'off' },
  },
  {
    files: ['gui/src/**/*.css'],
    language: 'css/css',
    plugins: { css },
    rules: { 'css/no-duplicate-imports': 'error', 'css/no-empty-blocks': 'error', 'css/no-invalid-at-rules': 'error' },
  },
  {
    files: ['gui/src/**/*.html'],
    ...html.configs['flat/recommended'],
    rules: {
      '@html-eslint/require-doctype': 'error',
      '@html-eslint/require-lang': 'error',
      '@html-eslint/require-title': 'error',
      '@html-eslint/require-meta-charset': 'error',
      '@html-eslint/no-duplicate-id': 'error',
      '@html-eslint/no-duplicate-attrs': 'error',
      '@html-eslint/no-trailing-spaces': 'error',
      '@html-eslint/no-restricted-attr-values': ['error',
        {
          attrPatterns: ['src', 'href'],
          attrValuePatterns: ['^(https?:)?//'],
          message: 'absolute URL: the pages work offline',
        }],
    },
  },
];
