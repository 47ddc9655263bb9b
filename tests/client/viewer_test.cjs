// SPDX-License-Identifier: AGPL-3.0-or-later
// The viewer pages of dotctl (fill-holes --report, view) in headless
// Chromium, driven by playwright-core: each page loads from its file with no
// console error and no request past the file, draws the mesh (canvas
// pixels), lists the holes exactly as the --json report does, highlights
// each filled hole's patch and flies to it, and shows the mesh before the
// fill with its holes' rims.
//
// node viewer_test.cjs DOTCTL MESH WORKDIR [SCREENSHOT.png]
// (NODE_PATH: the build's client/viewer/node_modules). Exit 77: no Chromium.
'use strict';
const {execFileSync} = require('child_process');
const fs = require('fs');
const path = require('path');
const {chromium} = require('playwright-core');

const [dotctl, mesh, work, screenshot] = process.argv.slice(2);
const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';
if (!fs.existsSync(CHROMIUM)) {
  console.log(`${CHROMIUM} not installed: skipped`);
  process.exit(77);
}

let failures = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) ++failures;
}

function dotctlJson(args) {
  let out;
  try {
    out = execFileSync(dotctl, args, {encoding: 'utf8'});
  } catch (e) {
    out = e.stdout;  // holes left open: exit 4, the JSON still printed
  }
  return JSON.parse(out);
}

// What the canvas shows, by colour class (viewer.js's palette, lit).
async function pixels(page) {
  return page.evaluate(() => {
    const src = document.querySelector('#view canvas');
    const c = document.createElement('canvas');
    c.width = src.width;
    c.height = src.height;
    const g = c.getContext('2d');
    g.drawImage(src, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    const n = {all: c.width * c.height, drawn: 0, patch: 0, selected: 0, open: 0, green: 0};
    for (let i = 0; i < d.length; i += 4) {
      const r = d[i], gr = d[i + 1], b = d[i + 2];
      if (Math.abs(r - 244) + Math.abs(gr - 244) + Math.abs(b - 242) > 12) ++n.drawn;
      if (r > gr && r - b > 80 && gr - b > 25) ++n.patch;
      if (b - r > 60 && b > gr) ++n.selected;
      if (r - gr > 100 && Math.abs(gr - b) < 45) ++n.open;
      if (gr > 2 * r + 30 && gr > 2 * b + 30) ++n.green;  // a file's own colour
    }
    return n;
  });
}

async function openPage(browser, file) {
  const page = await browser.newPage({viewport: {width: 1200, height: 700}});
  const errors = [], requests = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('request', (r) => requests.push(r.url()));
  await page.goto('file://' + path.resolve(file));
  await page.waitForFunction(() => window.dotViewer && window.dotViewer.ready,
                             null, {timeout: 30000});
  return {page, errors, requests};
}

async function settle(page) {
  await page.waitForFunction(() => window.dotViewer.settled(), null, {timeout: 10000});
}

(async () => {
  fs.mkdirSync(work, {recursive: true});
  const browser = await chromium.launch({
    executablePath: CHROMIUM,
    // As root in a container, with no GPU and no network.
    args: ['--no-sandbox', '--disable-gpu', '--use-angle=swiftshader',
           '--enable-unsafe-swiftshader', '--disable-quic', '--no-first-run',
           '--disable-background-networking', '--disable-component-update',
           '--disable-sync'],
  });
  try {
    // 1. A fill that leaves the largest hole open (--max-hole-edges).
    const report = path.join(work, 'report.html');
    const json = dotctlJson(['fill-holes', mesh, '--local', '-o',
                             path.join(work, 'filled.ply'), '--max-hole-edges', '40',
                             '--report', report, '--json']);
    check(json.page === report, `--json names the page (${json.page})`);
    const holes = json.report.holes;
    const filled = holes.filter((h) => h.status === 'HOLE_STATUS_FILLED').map((h) => h.id);
    check(filled.length >= 2 && filled.length < holes.length,
          `the fill leaves some holes open (${filled.length} of ${holes.length} filled)`);

    const {page, errors, requests} = await openPage(browser, report);
    const rows = await page.evaluate(() => window.dotViewer.holes());
    const want = holes.map((h) => ({
      id: h.id, edges: h.boundary_vertices,
      status: h.status.replace(/^HOLE_STATUS_/, '').toLowerCase()}));
    check(JSON.stringify(rows) === JSON.stringify(want),
          `the hole table is the JSON report's holes: ${JSON.stringify(rows)}`);
    const groups = (await page.evaluate(() => window.dotViewer.patchGroups())).sort();
    check(JSON.stringify(groups) === JSON.stringify([...filled].sort()),
          `one highlighted patch per filled hole: ${groups} (filled ${filled})`);

    const whole = await pixels(page);
    check(whole.drawn > 0.1 * whole.all,
          `the mesh is drawn (${(100 * whole.drawn / whole.all).toFixed(1)} % of the canvas)`);
    // Each hole's rim is its own loop: after the fill, the open holes'; before
    // it, every hole's.
    const openIds = holes.filter((h) => h.status !== 'HOLE_STATUS_FILLED').map((h) => h.id);
    const rimsAfter = (await page.evaluate(() => window.dotViewer.rimHoles(false))).sort();
    const rimsBefore = (await page.evaluate(() => window.dotViewer.rimHoles(true))).sort();
    check(JSON.stringify(rimsAfter) === JSON.stringify(openIds.sort()),
          `after: one rim per open hole: ${rimsAfter} (open ${openIds})`);
    check(JSON.stringify(rimsBefore) === JSON.stringify(holes.map((h) => h.id).sort()),
          `before: one rim per hole: ${rimsBefore}`);
    const open = openIds[0];
    await page.evaluate((h) => window.dotViewer.select(h), open);
    await settle(page);
    const rim = await pixels(page);
    check(rim.selected > 50,
          `hole ${open}, left open: the camera flies to its rim, shown selected (${rim.selected} px)`);

    for (const id of filled) {
      await page.evaluate((h) => window.dotViewer.select(h), id);
      await settle(page);
      const p = await pixels(page);
      const row = await page.evaluate(
          () => document.querySelector('#holes tbody tr.selected').dataset.hole);
      check(p.selected > 200 && Number(row) === id,
            `hole ${id}: the camera flies to its patch, shown selected (${p.selected} px)`);
    }

    await page.evaluate(() => window.dotViewer.showBefore(true));
    await page.evaluate((h) => window.dotViewer.select(h), filled[0]);
    await settle(page);
    const before = await pixels(page);
    check(before.patch === 0 && before.selected > 50,
          `before: hole ${filled[0]} open, its rim drawn selected (${before.selected} px), no patch`);
    await page.evaluate(() => window.dotViewer.showBefore(false));

    // Keys: a row chosen with Enter, b (or B) toggles before/after.
    await page.focus(`tr[data-hole="${filled[1]}"]`);
    await page.keyboard.press('Enter');
    check(await page.evaluate(() => window.dotViewer.selected()) === filled[1],
          `Enter on hole ${filled[1]}'s row selects it`);
    const pressed = () => page.evaluate(
        () => document.querySelector('#tools button').getAttribute('aria-pressed'));
    await page.keyboard.press('Shift+B');
    check(await pressed() === 'true', 'key B shows the mesh before the fill');
    await page.keyboard.press('b');
    check(await pressed() === 'false', 'key b shows the result again');

    if (screenshot) {
      await page.evaluate((h) => window.dotViewer.select(h), filled[0]);
      await settle(page);
      await page.screenshot({path: screenshot});
      console.log(`screenshot: ${screenshot}`);
    }
    check(errors.length === 0, `no console errors (${errors.join(' | ')})`);
    const outside = requests.filter((u) => !u.startsWith('file:') && !u.startsWith('data:'));
    check(outside.length === 0, `no request leaves the page (${outside.join(' ')})`);
    await page.close();

    // 2. dotctl view of the mesh as it is: its holes listed, nothing filled.
    const viewPage = path.join(work, 'view.html');
    const viewJson = dotctlJson(['view', mesh, '-o', viewPage, '--json']);
    check(viewJson.outcome === 'ok' && viewJson.output === viewPage,
          `dotctl view --json: ${viewJson.outcome}`);
    const v = await openPage(browser, viewPage);
    const viewRows = await v.page.evaluate(() => window.dotViewer.holes());
    check(viewRows.length === holes.length && viewRows.every((r) => r.status === 'listed'),
          `view lists the ${holes.length} holes (${viewRows.length})`);
    const drawn = await pixels(v.page);
    await v.page.evaluate((h) => window.dotViewer.select(h), filled[0]);
    await settle(v.page);
    const vp = await pixels(v.page);
    check(drawn.drawn > 0.1 * drawn.all && drawn.open > 0 && vp.patch === 0 && vp.selected > 50,
          `view draws the mesh and its rims (${drawn.open} px), hole ${filled[0]}'s selected (${vp.selected} px), no patch`);
    check(v.errors.length === 0, `view: no console errors (${v.errors.join(' | ')})`);

    // 3. A PLY's own vertex colours are drawn (an open pyramid, green).
    const ply = path.join(work, 'green.ply');
    fs.writeFileSync(ply, ['ply', 'format ascii 1.0', 'element vertex 4',
                           'property float x', 'property float y', 'property float z',
                           'property uchar red', 'property uchar green', 'property uchar blue',
                           'element face 3', 'property list uchar int vertex_indices',
                           'end_header', '0 0 0 0 255 0', '1 0 0 0 255 0', '0 1 0 0 255 0',
                           '0.3 0.3 1 0 255 0', '3 0 1 3', '3 1 2 3', '3 2 0 3', ''].join('\n'));
    const greenPage = path.join(work, 'green.html');
    check(dotctlJson(['view', ply, '-o', greenPage, '--json']).outcome === 'ok',
          'dotctl view of a coloured PLY');
    const g = await openPage(browser, greenPage);
    const {green} = await pixels(g.page);
    check(green > 1000, `the PLY's colours are drawn (${green} green px)`);
    check(g.errors.length === 0, `coloured page: no console errors (${g.errors.join(' | ')})`);
  } finally {
    await browser.close();
  }
  console.log(failures ? `${failures} checks failed` : 'all checks passed');
  process.exit(failures ? 1 : 0);
})().catch((e) => {
  console.error(e);
  process.exit(1);
});
