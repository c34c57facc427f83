// @ts-check
// Everything the library offers except loading the module and running it in a worker, shared by the two
// entries: index.js (browsers: adds loadSolver and SolverClient) and node.js (Node: adds the Node
// loader). Every function that needs the module takes it as its first argument (`solver`).

/** @typedef {import('./solver_module.js').SolverModule} SolverModule */
/** @typedef {import('./mesh.js').MeshData} MeshData */
/** @typedef {import('./mesh.js').CheckReport} CheckReport */
/** @typedef {import('./errors.js').Finding} Finding */
/** @typedef {import('./errors.js').ErrorData} ErrorData */
/** @typedef {import('../../build/wasm/solver_schema.js').ErrorCode} ErrorCode */
/** @typedef {import('./options.js').SolverOptions} SolverOptions */
/** @typedef {import('./options.js').OptionSchema} OptionSchema */
/** @typedef {import('./deformer.js').StepResult} StepResult */
/** @typedef {import('./deformer.js').IterationStats} IterationStats */
/** @typedef {import('./deformer.js').StopCode} StopCode */
/** @typedef {import('./cage.js').CageResult} CageResult */
/** @typedef {import('./weights.js').WeightsResult} WeightsResult */
/** @typedef {import('./coordinates.js').CoordinateType} CoordinateType */
/** @typedef {import('./coordinates.js').CoordinatesChoice} CoordinatesChoice */
/** @typedef {import('./deformer.js').CoordinatesReport} CoordinatesReport */
/** @typedef {import('./scene.js').Scene} Scene */
/** @typedef {import('./parts.js').VolumePartsSpec} VolumePartsSpec */
/** @typedef {import('./mesh.js').LayoutStats} LayoutStats */
/** @typedef {import('./model_io.js').Model} Model */
/** @typedef {import('./gltf.js').GltfModel} GltfModel */
/** @typedef {import('./examples.js').ExampleHandles} ExampleHandles */

export { BASES, Deformer, STOP_CODES } from './deformer.js';
export { FLOAT32_ABOVE_BYTES, singlePrecisionPays } from './basis_precision.js';
export { MAX_VOLUME_PARTS, checkVolumePartsSpec, volumeParts } from './parts.js';
export { MAX_JOINTS, checkSkeleton, skeletonWarnings } from './skeleton.js';
export { MESH_EXTENSIONS, assertMesh, checkMesh, checkPair, makeExample, readMesh, writeObj } from './mesh.js';
export { MODEL_EXTENSIONS, OUTPUT_EXTENSIONS, isGltfFile, readModel, writeModel } from './model_io.js';
export { GLTF_EXTENSIONS, meshToGlb, readGltf, writeGltf } from './gltf.js';
export { MAX_GLTF_OBJECTS } from './gltf_check.js';
export { layoutNormals, normalGroups } from './normals.js';
export { EXAMPLE_NAMES, exampleNames, loadExample } from './examples.js';
export { CAGE_LIMITS, generateCage, meshFromCells } from './cage.js';
export { computeWeights } from './weights.js';
export { COORDINATES, checkCoordinates } from './coordinates.js';
export { MAX_FILE_BYTES, checkFileSize } from './file_limits.js';
export { containedPath, containedUri } from './contained_path.js';
export { handleTargets, parseScene, parseSceneHandles } from './scene.js';
export { checkHandleLine, handleLineWarnings, lineOfCamera } from './handle_lines.js';
export {
  DEFAULT_OPTIONS, JACOBIANS, METHODS, OPTIONS, OPTION_NAMES, checkSolverOptions, describeValue, optionAllows, optionSchema,
} from './options.js';
export {
  CODES_BY_CLASS, CancelledError, InputError, MeshError, SolverError, SubspaceDeformError, errorFromData,
  errorToData, typedError,
} from './errors.js';
/** Every error code (from the C++ enum, cpp/core/error.h) and every stop code with its meaning. */
export { ERROR_CODES } from '../../build/wasm/solver_schema.js';
