// SPDX-License-Identifier: GPL-2.0-or-later
// Opens a page of `kanegen animate --format html` in headless Chromium from
// file:// and reads what it draws through its window.kanegen API (the
// three.js groups' world matrices). check_html.py says what to read, in a
// JSON plan, and compares; this prints one JSON object on stdout.
// times: "page" reads at every frame's time.
//   node probe_page.js PLAN.json
// Plan: {page, viewer (the folder of node_modules), chromium, times: [t...],
// scales: [s...], bodies: [name...], beams: [name...], columns: [plotted column...],
// screenshot (a PNG path), play_seconds, controls (a beam whose nodes the magnification moves)}.
'use strict';
const fs = require('fs');
const path = require('path');

async function readAt(page, plan) {
  const at = [];
  const times = plan.times === 'page' ? await page.evaluate(() => window.kanegen.times()) : plan.times || [];
  for (const scale of plan.scales || [])
    for (const t of times)
      at.push(await page.evaluate(([t, scale, bodies, beams]) => {
        const k = window.kanegen;
        k.setScale(scale);
        k.setTime(t);
        const out = { t: k.time(), scale, bodies: {}, nodes: {} };
        for (const name of bodies) out.bodies[name] = k.bodyPosition(name);
        for (const name of beams) out.nodes[name] = k.nodePositions(name);
        return out;
      }, [t, scale, plan.bodies || [], plan.beams || []]));
  return at;
}

/** Plays for a while at speed 1: how far the time moved, and the frames drawn per second. */
async function play(page, seconds) {
  return page.evaluate(async (seconds) => {
    const k = window.kanegen, wait = (ms) => new Promise((done) => setTimeout(done, ms));
    k.setTime(k.times()[0]);
    k.play();
    await wait(500);  // past the first frames' shader compilation
    const t0 = k.time(), f0 = k.framesDrawn(), w0 = performance.now();
    await wait(1000 * seconds);
    const t1 = k.time(), f1 = k.framesDrawn(), w1 = performance.now();
    k.pause();
    return { t0, t1, frames: f1 - f0, seconds: (w1 - w0) / 1000, fps: (f1 - f0) / ((w1 - w0) / 1000) };
  }, seconds);
}

/** The controls as a user works them: the play button, the slider, the speed and the magnification. */
async function useControls(page, beam) {
  const k = (f, arg) => page.evaluate(f, arg);
  const out = {};
  await page.selectOption('#speed', '0.25');
  await k(() => window.kanegen.setTime(window.kanegen.times()[0]));
  await page.click('#play');
  out.playingAfterClick = await k(() => window.kanegen.playing());
  await page.waitForTimeout(400);
  await page.click('#play');
  out.pausedAfterClick = !(await k(() => window.kanegen.playing()));
  out.timeAfterPlay = await k(() => window.kanegen.time());
  await k(() => { const s = document.getElementById('slider'); s.value = s.max; s.dispatchEvent(new Event('input')); });
  out.timeAfterSlider = await k(() => window.kanegen.time());
  const before = await k((name) => window.kanegen.nodePositions(name), beam);
  await page.fill('#scale', '0');
  out.nodesMoveWithScale = JSON.stringify(before) !== JSON.stringify(await k((name) => window.kanegen.nodePositions(name), beam));
  return out;
}

/** What the page shows of the names: each must come back as the text it was. */
async function names(page) {
  return page.evaluate(() => ({
    title: document.title,
    model: document.getElementById('model').textContent,
    bodies: Array.from(document.querySelectorAll('#bodies li'), (li) => li.textContent),
    columns: Array.from(document.getElementById('columns').options, (o) => o.textContent),
    scripts: document.scripts.length,
    elements: document.getElementsByTagName('*').length,
    pwned: window.pwned !== undefined,
    api: window.kanegen ? window.kanegen.bodyNames() : null,
  }));
}

async function main() {
  const plan = JSON.parse(fs.readFileSync(process.argv[2], 'utf8'));
  const { chromium } = require(path.join(plan.viewer, 'node_modules', 'playwright-core'));
  // No sandbox: CI runs as root in a VM, where chromium's sandbox cannot start; the page is the test's own.
  const browser = await chromium.launch({ executablePath: plan.chromium, args: ['--no-sandbox'] });
  const result = { errors: [] };
  try {
    const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
    page.on('pageerror', (e) => result.errors.push('page error: ' + e.message));
    page.on('console', (m) => { if (m.type() === 'error') result.errors.push('console: ' + m.text()); });
    page.on('request', (r) => { if (!r.url().startsWith('file:') && !r.url().startsWith('data:')) result.errors.push('request: ' + r.url()); });
    await page.goto('file://' + path.resolve(plan.page));
    await page.waitForFunction(() => window.kanegen && window.kanegen.framesDrawn() > 0, null, { timeout: 20000 });
    result.names = await names(page);
    result.at = await readAt(page, plan);
    if (plan.columns)  // the plotted columns, picked as a user would
      await page.evaluate((names) => {
        const list = document.getElementById('columns');
        for (const option of list.options) option.selected = names.includes(option.textContent);
        list.dispatchEvent(new Event('change'));
        window.kanegen.setTime(window.kanegen.time());
      }, plan.columns);
    if (plan.screenshot) await page.screenshot({ path: plan.screenshot });  // at the last time and scale read
    if (plan.play_seconds) result.played = await play(page, plan.play_seconds);
    if (plan.controls) result.controls = await useControls(page, plan.controls);
  } finally {
    await browser.close();
  }
  process.stdout.write(JSON.stringify(result) + '\n');
}

main().catch((e) => { process.stderr.write(String(e && e.stack || e) + '\n'); process.exit(1); });
