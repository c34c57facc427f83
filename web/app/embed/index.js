// Entry of the embed bundle (dist/subspace-deformer.js): defines <subspace-deformer> and exports mount().
//   <script type="module" src="subspace-deformer.js"></script>
//   <subspace-deformer example="bar"></subspace-deformer>
import { defineElement, mount, SubspaceDeformerElement } from './subspace_deformer_element.js';

defineElement();

export { mount, SubspaceDeformerElement, defineElement };
