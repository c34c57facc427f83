// The tool strip's icons: 24 x 24 stroke drawings (SVG path data), so they need no font or image file and scale
// with the button. Each is drawn in currentColor.
const ICONS = {
  orbit: 'M20 12a8 8 0 1 1-2.3-5.7M20 4v5h-5',
  pick: 'M12 3v5M12 16v5M3 12h5M16 12h5M12 10.5a1.5 1.5 0 1 0 0 3a1.5 1.5 0 1 0 0-3',
  brush: 'M4 20c2.5 0 4.5-1.2 4.5-3.8l8.8-8.8a1.8 1.8 0 0 0-2.6-2.6l-8.8 8.8C3.4 13.6 4 17.5 4 20zM13 7l4 4',
  lasso: 'M12 4c4.4 0 8 2.2 8 5s-3.6 5-8 5s-8-2.2-8-5s3.6-5 8-5zM7 13c-1.5 2-.5 4.5 1.5 5.5M8.5 18.5l-1 2.5',
  bone: 'M6.5 4.5a2 2 0 1 0-2 2l2.5 1 9 9 1 2.5a2 2 0 1 0 2-2l-2.5-1-9-9zM7 7l10 10',
  erase: 'M4 15.5l8.5-8.5a2 2 0 0 1 2.8 0l3.2 3.2a2 2 0 0 1 0 2.8L12 19.5H8zM9 10.5l5.5 5.5M12 19.5h8',
  fixed: 'M7 11h10v9H7zM9 11V8a3 3 0 0 1 6 0v3',
  moving: 'M12 3v18M3 12h18M12 3l-3 3M12 3l3 3M12 21l-3-3M12 21l3-3M3 12l3-3M3 12l3 3M21 12l-3-3M21 12l-3 3',
  translate: 'M5 19L19 5M19 5h-6M19 5v6M5 19h6M5 19v-6',
  rotate: 'M6 14a7 7 0 1 0 2-7.5M8 3v4h4',
  undo: 'M9 14L4 9l5-5M4 9h10a6 6 0 0 1 0 12h-3',
  redo: 'M15 14l5-5-5-5M20 9H10a6 6 0 0 0 0 12h3',
  fit: 'M4 9V4h5M15 4h5v5M20 15v5h-5M9 20H4v-5M9 9h6v6H9z',
  pause: 'M8 5v14M16 5v14',
  play: 'M7 4l12 8-12 8z',
  step: 'M6 5l9 7-9 7zM18 5v14',
  help: 'M9.5 9a2.5 2.5 0 1 1 3.5 2.3c-.7.3-1 .9-1 1.7v1M12 18v.5M12 2.5a9.5 9.5 0 1 0 0 19a9.5 9.5 0 1 0 0-19',
  panel: 'M4 6h16M4 12h16M4 18h16',
  lesson: 'M4 5h6a2 2 0 0 1 2 2v13a2 2 0 0 0-2-2H4zM20 5h-6a2 2 0 0 0-2 2v13a2 2 0 0 1 2-2h6z',
};

/** An <svg> element drawing the named icon. */
export function icon(name) {
  const svg = document.createElementNS('http://www.w3.org/2000/svg', 'svg');
  svg.setAttribute('viewBox', '0 0 24 24');
  svg.setAttribute('aria-hidden', 'true');
  svg.setAttribute('class', 'sd-icon');
  const path = document.createElementNS('http://www.w3.org/2000/svg', 'path');
  path.setAttribute('d', ICONS[name]);
  svg.appendChild(path);
  return svg;
}
