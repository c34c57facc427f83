// The JS copies of limits the C++ keeps (the library checks them before calling wasm, with messages of its own):
// each must equal the C++ constant, read from its header's text, so that a change on one side fails here.
import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import { MAX_MESH_COORDINATE } from '../../web/lib/mesh.js';
import { MAX_WASM_ALLOCATION_BYTES } from '../../web/lib/wasm_allocation.js';

const header = (path) => readFileSync(new URL(`../../cpp/core/${path}`, import.meta.url), 'utf8');

/** The right-hand side of `constexpr <type> name = ...;` in `text` (the first, or the one after `after`). */
function constant(text, name, after = '') {
  const from = after ? text.indexOf(after) : 0;
  expect(from).toBeGreaterThanOrEqual(0);
  const match = new RegExp(`constexpr [\\w:]+ ${name} = ([^;]+);`).exec(text.slice(from));
  expect(match, `${name} in the header`).not.toBeNull();
  return match[1].trim();
}

describe('limits the JS library shares with the C++', () => {
  it('MAX_MESH_COORDINATE is kMaxMeshCoordinate (core/mesh/mesh_check.h)', () => {
    expect(Number(constant(header('mesh/mesh_check.h'), 'kMaxMeshCoordinate'))).toBe(MAX_MESH_COORDINATE);
  });

  it('MAX_WASM_ALLOCATION_BYTES is the wasm build\'s kMaxAllocationBytes (core/basis/mean_value_coordinates.h)', () => {
    const text = constant(header('basis/mean_value_coordinates.h'), 'kMaxAllocationBytes', '#ifdef __EMSCRIPTEN__');
    // "(std::size_t(1) << 31) - (std::size_t(1) << 20)": evaluated as the shifts and sums it is made of.
    const js = text.replace(/std::size_t\((\d+)\)/g, '$1');
    expect(js).toMatch(/^[\d\s()<+-]+$/);
    const value = Function(`return ${js.replace(/(\d+) << (\d+)/g, '($1 * 2 ** $2)')};`)();
    expect(value).toBe(MAX_WASM_ALLOCATION_BYTES);
  });
});
