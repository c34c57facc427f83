// Adds up the suites' results into the one closing line CI reads:
//   total: N passed, M failed, K skipped
// Inputs in <dir>: ctest.xml (JUnit from ctest), vitest.json and vitest-single.json (Vitest JSON reporter,
// the threaded and the single-threaded wasm build), e2e.json
// ({passed, failed, skipped} from tests/e2e/run.mjs). A missing file means that suite did not run: failure.
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';

const dir = process.argv[2] ?? 'test-results';
const totals = { passed: 0, failed: 0, skipped: 0 };
let missing = [];

function add(name, counts) {
  if (!counts) {
    missing.push(name);
    return;
  }
  for (const key of Object.keys(totals)) totals[key] += counts[key];
  console.log(`${name}: ${counts.passed} passed, ${counts.failed} failed, ${counts.skipped} skipped`);
}

function ctestCounts(file) {
  if (!existsSync(file)) return null;
  const xml = readFileSync(file, 'utf8');
  const cases = xml.match(/<testcase\b[^>]*?(\/>|>[\s\S]*?<\/testcase>)/g) ?? [];
  const counts = { passed: 0, failed: 0, skipped: 0 };
  for (const c of cases) {
    if (/status="(fail|failed)"|<failure/.test(c)) counts.failed++;
    else if (/status="(notrun|skipped|disabled)"|<skipped/.test(c)) counts.skipped++;
    else counts.passed++;
  }
  return counts;
}

function vitestCounts(file) {
  if (!existsSync(file)) return null;
  const r = JSON.parse(readFileSync(file, 'utf8'));
  return { passed: r.numPassedTests, failed: r.numFailedTests + (r.success === false && r.numFailedTests === 0 ? 1 : 0), skipped: r.numPendingTests + r.numTodoTests };
}

function e2eCounts(file) {
  if (!existsSync(file)) return null;
  const r = JSON.parse(readFileSync(file, 'utf8'));
  return { passed: r.passed, failed: r.failed, skipped: r.skipped ?? 0 };
}

add('native', ctestCounts(join(dir, 'ctest.xml')));
add('js', vitestCounts(join(dir, 'vitest.json')));
add('js (single-threaded build)', vitestCounts(join(dir, 'vitest-single.json')));
add('browser', e2eCounts(join(dir, 'e2e.json')));
if (missing.length) {
  console.log(`suites that produced no results: ${missing.join(', ')}`);
  totals.failed += missing.length;
}
console.log(`total: ${totals.passed} passed, ${totals.failed} failed, ${totals.skipped} skipped`);
process.exitCode = totals.failed > 0 ? 1 : 0;
