// @ts-check
// The shapes of what a Deformer session returns (deformer.js): iteration statistics, step results, the reduced
// integration's fit, ARAP half steps and the cage's quality. Types only (JSDoc), for the declarations and editors.

/** @typedef {import('./mesh.js').MeshData} MeshData */
/**
 * @typedef {object} IterationStats
 * @property {number} iteration counted from the last reset
 * @property {number} merit 1/2 |f|^2 + R(P) + lambda g
 * @property {number} energy 1/2 |f|^2
 * @property {number} laplacianEnergy
 * @property {number} positionEnergy
 * @property {number} straightnessEnergy the bones' soft straightness term (option straightnessWeight; else 0)
 * @property {number} regularizationEnergy R(P), the cage subspace's cage regularisation (else 0)
 * @property {number} volume
 * @property {number} volumeRelError (volume - rest volume) / rest volume
 * @property {number} lambda volume multiplier (0 with several volume parts: see partLambda)
 * @property {number[]} [partVolumeChange] with volume parts: each part's (V - V rest) / |V rest|
 * @property {number[]} [partLambda] with volume parts: each part's multiplier
 * @property {number} [boneLengthError] with a skeleton: the largest |length - rest length| / rest length
 * @property {number} [boneStraightnessError] with a skeleton: the largest distance of a bone's samples from it / its length
 * @property {number[]} [boneLambda] with a skeleton: each bone's length multiplier
 * @property {number} step largest vertex displacement of the iteration
 * @property {number} meritStart Gauss-Newton: the merit at the start of the iteration, with this step's lambda
 * @property {number} slope Gauss-Newton: d merit / d alpha along the step at alpha = 0 (negative: descent)
 * @property {number} stepLength Gauss-Newton: largest vertex move of the full step (alpha = 1)
 * @property {number} alpha Gauss-Newton: the accepted step length (0: no step taken)
 * @property {LineSearchTrial[]} lineSearch Gauss-Newton: every line-search trial in order (empty for ARAP)
 * @property {number} lineSearchTrials
 * @property {number} innerIterations CG iterations (fast mode)
 * @property {number} products matrix-free products W^T J^T J W v (fast subspace)
 * @property {number} passes streams over W
 * @property {number} samples reduced integration: the vertices its rule reads (the clusters' centres, or every vertex
 *   of a small mesh); 0 with full integration
 * @property {boolean} finishing reduced integration: an iteration on the energy of every vertex after the rule's
 *   iterations converged, which brings the shape to the full integration's (docs/method.md section 17.3; samples 0)
 * @property {number} ms
 */
/**
 * The reduced integration's rule (docs/method.md section 17).
 * @typedef {object} ReducedIntegrationInfo
 * @property {boolean} fitted made yet (on the first reduced solve, or prepareReduced())
 * @property {string} rule 'clusters' (one rotation per cluster of vertices: meshes above max(800, 2m) vertices) or
 *   'every vertex' (the exact sum, on smaller meshes)
 * @property {number} samples the clusters (each read at its centre's one-ring), or the vertices summed
 * @property {number} candidates the mesh's vertices
 * @property {number} testError the rule's gradient error relative to the part it approximates, the median over
 *   eight held-out poses (0 for the exact sum)
 * @property {boolean} reliable the test error is at most 0.25 (kReducedTestErrorLimit); when not, a reduced
 *   solve may converge to another shape than the full one, and the app drags with full integration instead
 * @property {number} ms time to make the rule
 */
/**
 * One trial of the Armijo line search.
 * @typedef {object} LineSearchTrial
 * @property {number} alpha the step length tried
 * @property {number} merit the merit there, before volume restoration
 * @property {boolean} sufficientDecrease it passed the Armijo test
 * @property {boolean} restored and its volume could be restored: the accepted trial
 */
/**
 * One half of an ARAP local-global iteration (arapHalfStep).
 * @typedef {object} ArapHalfStep
 * @property {'local'|'global'} phase
 * @property {number} energyBefore ARAP energy with the rotations and positions before the half step
 * @property {number} energyAfter the same after it (never higher)
 * @property {number} meanRotation mean angle of the vertices' rotations after it (radians)
 * @property {number} maxRotation largest angle (radians)
 * @property {number} step largest vertex move (0 for the local step)
 */
/**
 * Why a step() or solve() call returned (cpp/core/solver/solver_types.h, generated with the schema).
 * @typedef {import('../../build/wasm/solver_schema.js').StopCode} StopCode
 */
/**
 * @typedef {object} StepResult
 * @property {IterationStats[]} iterations
 * @property {boolean} converged
 * @property {StopCode} stop why the call returned: decide from this
 * @property {string} stopReason the same for people (may say more, e.g. what was not finite)
 */
/**
 * How well the cage controls the mesh, read from W (cpp/core/basis/cage_quality.h, docs/cage.md).
 * @typedef {object} CageQuality
 * @property {number} cageVertices
 * @property {number} weakVertices cage vertices with no weight above 1e-3 on any mesh vertex
 * @property {number} minColumnMax the smallest of the cage vertices' largest weights
 * @property {number} volumeRatio cage volume / mesh volume
 * @property {number} influenceRatio smallest / largest eigenvalue of W^T W over sampled rows (NaN: not
 *   computed, cages over 400 vertices): tiny when cage motions exist that barely move the mesh
 * @property {number} weakMotions eigenvalues below 1e-6 of the largest
 * @property {number} sampledRows rows of W in that W^T W
 * @property {number} ms time taken
 * @property {string[]} warnings one sentence per exceeded threshold
 * @property {string[]} warningCodes their codes: weak_cage_vertices, weak_cage_motions, loose_cage
 * @property {boolean} poor true when there is a warning
 */

export {};
