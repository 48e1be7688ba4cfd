// The side panel and the legend of the 3-D view: what is shown, the
// suggestions and worst regions to click, and the picked face's values.
import { EXISTING_COLOUR, suggestionColour } from './frustums.js';
import { FLAG_LOW_TEXTURE, FLAG_TWO_VIEWS, FLAG_UNOBSERVED } from './surface.js';

// Four significant digits, as the report's tables.
export function formatNumber(v) {
  if (v === null || v === undefined || Number.isNaN(v)) return '—';
  if (!Number.isFinite(v)) return String(v);
  if (v !== 0 && (Math.abs(v) >= 1e5 || Math.abs(v) < 1e-3)) return v.toExponential(3);
  return String(Number(v.toPrecision(4)));
}

function element(tag, className, text) {
  const el = document.createElement(tag);
  if (className) el.className = className;
  if (text !== undefined) el.textContent = text;
  return el;
}

function swatch(css) {
  const s = element('span', 'mnv-swatch');
  s.style.background = css;
  return s;
}

const rgb = ([r, g, b]) => `rgb(${r},${g},${b})`;

export class Panel {
  constructor(container, data, actions) {
    this.data = data;
    this.actions = actions;
    this.legend = this.buildLegend();
    const side = element('div', 'mnv-side');
    container.appendChild(side);

    const toolbar = element('div', 'mnv-toolbar');
    const home = element('button', 'mnv-item', 'Overview (whole mesh)');
    home.addEventListener('click', () => actions.overview());
    toolbar.appendChild(home);
    for (const [what, label, css] of [
      ['cameras', `existing cameras (${data.cameras.length})`, rgb(EXISTING_COLOUR)],
      ['suggestions', `suggested views (${data.suggestions.length})`, rgb(suggestionColour(0, 1))],
      ['weak', 'stripe weak evidence', null],
    ]) {
      const row = element('label');
      const box = element('input');
      box.type = 'checkbox';
      box.checked = true;
      box.addEventListener('change', () => actions.toggle(what, box.checked));
      row.append(box, ' ');
      if (css) row.appendChild(swatch(css));
      else row.appendChild(Object.assign(swatch(''), { className: 'mnv-swatch mnv-stripes' }));
      row.append(label);
      toolbar.appendChild(row);
    }
    side.appendChild(toolbar);

    side.appendChild(element('h3', '', 'Suggested views: click to look through'));
    this.suggestionButtons = data.suggestions.map((s, i) => {
      const region = data.regions[s.region];
      const b = element('button', 'mnv-item');
      b.append(swatch(rgb(suggestionColour(i, data.suggestions.length))),
        `${s.label}: energy ${formatNumber(s.energy.total)}, sees ${s.seen_faces.length}/${region ? region.faces.length : 0} worst faces of region ${s.region + 1}`);
      b.addEventListener('click', () => actions.lookThrough(i));
      side.appendChild(b);
      return b;
    });

    side.appendChild(element('h3', '', 'Worst regions: click to frame'));
    this.regionButtons = data.regions.map((r, i) => {
      const b = element('button', 'mnv-item',
        `region ${i + 1}: ${r.faces.length} faces, worst PRI ${formatNumber(r.worst_pri)}`);
      b.addEventListener('click', () => actions.frameRegion(i));
      side.appendChild(b);
      return b;
    });

    side.appendChild(element('h3', '', 'Selection'));
    this.info = element('div', 'mnv-picked', 'Click a face to read its values.');
    side.appendChild(this.info);
  }

  buildLegend() {
    const d = this.data;
    const legend = element('div', 'mnv-legend');
    legend.appendChild(element('div', '', `PRI (${d.measure}), 5th..95th percentile`));
    const scale = element('div');
    const ends = element('span', 'mnv-ends');
    ends.append(element('span', '', `${formatNumber(d.range[1])} worst`), element('span', '', `${formatNumber(d.range[0])} best`));
    scale.append(element('span', 'mnv-bar'), ends);
    legend.appendChild(scale);
    const flags = d.array('display_flags');
    let unobserved = 0;
    let weak = 0;
    for (const f of flags) {
      if (f & FLAG_UNOBSERVED) ++unobserved;
      else if (f & (FLAG_TWO_VIEWS | FLAG_LOW_TEXTURE)) ++weak;
    }
    const faces = d.decimated ? 'display faces' : 'faces';
    for (const [css, text] of [
      ['rgb(160,160,160)', `unobserved (${unobserved} ${faces})`],
      ['stripes', `weak evidence (${weak}): 2 views only or low texture`],
      ['rgb(255,0,255)', 'selected region'],
      ['rgb(0,217,255)', 'picked face'],
    ]) {
      const row = element('div', 'mnv-key');
      row.appendChild(css === 'stripes' ? Object.assign(swatch(''), { className: 'mnv-swatch mnv-stripes' }) : swatch(css));
      row.append(text);
      legend.appendChild(row);
    }
    
    return legend;
  }

  setStatus(status, d) {
    let text = d.decimated ? `display mesh decimated from ${d.faces} to ${d.display_faces} faces` : `${d.faces} faces`;
    if (d.interaction) text += `; ${d.interaction.faces} faces while turning`;
    status.textContent = text;
  }

  setActive(suggestion, region) {
    this.suggestionButtons.forEach((b, i) => b.classList.toggle('active', i === suggestion));
    this.regionButtons.forEach((b, i) => b.classList.toggle('active', i === region));
  }

  table(rows) {
    const t = element('table');
    for (const [k, v] of rows) {
      const tr = element('tr');
      tr.append(element('td', '', k), element('td', '', v));
      t.appendChild(tr);
    }
    return t;
  }

  showView(s) {
    this.info.textContent = '';
    this.info.append(
      element('div', '', `Looking through ${s.label} (${s.source}): its pose and intrinsics; drag to leave.`),
      this.table([
        ['centre', s.centre.map((v) => v.toFixed(3)).join(', ')],
        ['fx, fy', `${formatNumber(s.fx)}, ${formatNumber(s.fy)}`],
        ['cx, cy', `${formatNumber(s.cx)}, ${formatNumber(s.cy)}`],
        ['image', `${s.width} x ${s.height}`],
        ['energy', formatNumber(s.energy.total)],
      ]),
    );
  }

  showRegion(i, r, labels) {
    this.info.textContent = '';
    this.info.append(
      element('div', '', `Region ${i + 1} (magenta): the ${r.faces.length} worst faces set for it.`),
      this.table([
        ['worst PRI', formatNumber(r.worst_pri)],
        ['suggested views', labels.length ? labels.join(', ') : 'none'],
      ]),
    );
  }

  showPicked(p) {
    this.info.textContent = '';
    if (!p) {
      this.info.textContent = 'No face there.';
      return;
    }
    const rows = [
      ['face', String(p.face)],
      [`PRI (${this.data.measure})`, formatNumber(p.pri)],
      ['views', String(p.views)],
      ['pairs compared', String(p.pairs)],
      ['samples per view', String(p.samples)],
      ['texture', formatNumber(p.texture)],
      ['evidence', p.evidence.length ? p.evidence.join('; ') : 'enough'],
      ['seen by', p.suggestions.length ? p.suggestions.join(', ') : 'no suggestion'],
      ['worst region', p.region === null ? '—' : String(p.region + 1)],
    ];
    if (this.data.decimated) rows.push(['display face', `${p.display_face}, stands for ${p.stands_for} faces`]);
    const t = this.table(rows);
    t.dataset.face = String(p.face);
    t.querySelectorAll('tr')[1].lastChild.className = 'mnv-pri';
    this.info.appendChild(t);
  }
}
