// subspace-deform, the Node entry (package.json "exports", condition "node"): the library plus the Node
// loader, which reads the .wasm bytes itself (load_node.js). loadSolver() is that loader here, so the same
// code runs in Node and in a browser:
//
//   import { loadSolver, Deformer, readMesh } from 'subspace-deform';
//   const solver = await loadSolver();                    // or loadSolver({ bench: true }) for benchmarks
export * from './library.js';
export { loadNodeSolver as loadSolver, loadNodeSolver, wasmDir } from './load_node.js';
