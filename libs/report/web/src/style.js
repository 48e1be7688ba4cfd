// The viewer's styles, added to the page once (the report's page keeps its own).
const CSS = `
.mnv{display:flex;gap:10px;align-items:stretch;margin:1em 0;font-size:13px}
.mnv-stage{position:relative;flex:1 1 auto;min-width:320px;height:560px;border:1px solid #ccc;background:#fff;overflow:hidden}
.mnv-stage canvas{display:block;width:100%;height:100%;cursor:grab}
.mnv-side{flex:0 0 290px;max-height:562px;overflow-y:auto}
.mnv-side h3{font-size:13px;margin:0.8em 0 0.3em}
.mnv-side button.mnv-item{display:block;width:100%;text-align:left;margin:2px 0;padding:3px 6px;border:1px solid #bbb;border-radius:3px;background:#f7f7f7;cursor:pointer;font:inherit}
.mnv-side button.mnv-item:hover{background:#e8eefc}
.mnv-side button.mnv-item.active{background:#dde6fb;border-color:#4a6fd0}
.mnv-swatch{display:inline-block;width:10px;height:10px;margin-right:5px;vertical-align:-1px;border:1px solid #555}
.mnv-legend{position:absolute;top:8px;right:8px;max-width:190px;background:rgba(255,255,255,0.88);border:1px solid #bbb;padding:5px 7px;line-height:1.3;font-size:12px}
.mnv-legend .mnv-bar{display:inline-block;width:14px;height:90px;border:1px solid #444;background:linear-gradient(to top,rgb(0,255,0),rgb(255,255,0),rgb(255,0,0));vertical-align:top}
.mnv-legend .mnv-ends{display:inline-flex;flex-direction:column;justify-content:space-between;height:92px;margin-left:5px;vertical-align:top}
.mnv-legend .mnv-key{margin-top:4px}
.mnv-stripes{background:repeating-linear-gradient(45deg,#45455a 0 2px,#8fdc8f 2px 7px)}
.mnv-status{position:absolute;left:8px;bottom:6px;background:rgba(255,255,255,0.85);padding:2px 6px;color:#333}
.mnv-label{position:absolute;transform:translate(4px,-100%);padding:0 4px;font:11px sans-serif;border-radius:2px;border:1px solid rgba(0,0,0,0.4);cursor:pointer;white-space:nowrap}
.mnv-frame{position:absolute;border:2px dashed rgba(40,40,40,0.7);pointer-events:none;display:none}
.mnv-picked table{border-collapse:collapse;margin:0.3em 0}
.mnv-picked td{border:1px solid #ccc;padding:1px 6px;text-align:left}
.mnv-toolbar label{display:block}
.mnv-error{color:#a00;padding:1em}
`;

export function addStyles(doc) {
  if (doc.getElementById('mnv-styles')) return;
  const style = doc.createElement('style');
  style.id = 'mnv-styles';
  style.textContent = CSS;
  doc.head.appendChild(style);
}
