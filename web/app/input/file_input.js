// Files into the app: dropped on it (with a hint over the page while dragging) or chosen with the file
// picker (openPicker(), the panel's "open" buttons). Both hand the files to the app's loadFiles; failures
// are shown in the page by the loader, so they are not rethrown here.
// connect() / disconnect() / dispose() as three.js controls do.

export class FileInput {
  /**
   * @param {HTMLElement} element the app's root: the drop target, and the parent of the hint and the input
   * @param {(files: File[]) => Promise<unknown>} load
   */
  constructor(element, load) {
    this.element = element;
    this.load = load;
    this.depth = 0; // dragenter/dragleave nesting over child elements
    this.hint = Object.assign(document.createElement('div'), { className: 'sd-drop' });
    this.hint.textContent = 'Drop a mesh (OBJ, OFF, PLY, STL, glTF) and its cage, or a scene (.json)';
    this.picker = Object.assign(document.createElement('input'), { type: 'file', multiple: true, hidden: true });
    this.picker.accept = '.obj,.off,.ply,.stl,.glb,.gltf,.bin,.png,.jpg,.jpeg,.webp,.json';
    element.append(this.hint, this.picker);
    /** [target, event type, listener] for connect() / disconnect() */
    this.bindings = [
      [element, 'dragenter', (e) => this.onDragEnter(e)],
      [element, 'dragover', (e) => e.preventDefault()],
      [element, 'dragleave', () => this.onDragLeave()],
      [element, 'drop', (e) => this.onDrop(e)],
      [this.picker, 'change', () => this.onPicked()],
    ];
    this.connect();
  }

  connect() {
    for (const [target, type, listener] of this.bindings) target.addEventListener(type, listener);
  }

  disconnect() {
    for (const [target, type, listener] of this.bindings) target.removeEventListener(type, listener);
  }

  dispose() {
    this.disconnect();
    this.hint.remove();
    this.picker.remove();
  }

  /** Opens the browser's file chooser. */
  openPicker() {
    this.picker.click();
  }

  onDragEnter(event) {
    event.preventDefault();
    this.depth++;
    this.element.classList.add('sd-dragover');
  }

  onDragLeave() {
    if (--this.depth <= 0) this.element.classList.remove('sd-dragover');
  }

  onDrop(event) {
    event.preventDefault();
    this.depth = 0;
    this.element.classList.remove('sd-dragover');
    const files = [...(event.dataTransfer?.files ?? [])];
    if (files.length) this.load(files).catch(() => {});
  }

  onPicked() {
    const files = [...this.picker.files];
    this.picker.value = ''; // the same file can be chosen again
    this.load(files).catch(() => {});
  }
}
