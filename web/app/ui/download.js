// Saves text or a data URL as a file through a temporary <a download> link.
export function downloadText(text, filename, type = 'text/plain') {
  const url = URL.createObjectURL(new Blob([text], { type }));
  clickLink(url, filename);
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

export function downloadDataUrl(dataUrl, filename) {
  clickLink(dataUrl, filename);
}

function clickLink(href, filename) {
  const a = document.createElement('a');
  a.href = href;
  a.download = filename;
  a.style.display = 'none';
  document.body.appendChild(a);
  a.click();
  a.remove();
}
