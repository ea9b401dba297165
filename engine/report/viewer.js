/* aalab report viewer: every method's frame, the reference, the difference and the FLIP map at full
 * resolution, zoomed (nearest neighbour) and panned together; an A/B pane flipped with F; a pixel
 * inspector; frame scrubber and playback; the per-frame PSNR chart picks the frame. No frameworks, no
 * network: images come from viewer/NNNN.js beside the page (report_viewer.c says why). */
(function () {
"use strict";
const D = JSON.parse(document.getElementById("aa-viewer-data").textContent);
const root = document.getElementById("viewer");
const W = D.width, H = D.height, N = D.frames.length, M = D.methods.length;
const REF = -1; /* source id of the reference; methods are 0..M-1 */
const ZOOMS = [1, 2, 4, 8, 16, 32];
const S = {
	frame: 0, shown: -1, zoom: 1, cx: W / 2, cy: H / 2, px: -1, py: -1, hover: false,
	mode: "abs", gain: 4, against: REF, threshold: 0.01, a: Math.max(0, M - 1), b: REF, showB: false,
	playing: false, fps: D.fps, playedFrames: 0, playStart: 0, measuredFps: 0, drawMs: 0
};
const api = window.aalabViewer = { ready: false, state: () => Object.assign({}, S, view()) };

function el(tag, attrs, ...kids) {
	const e = document.createElement(tag);
	for (const k in attrs || {}) {
		if (k.startsWith("on")) e.addEventListener(k.slice(2), attrs[k]);
		else e.setAttribute(k, attrs[k]);
	}
	for (const k of kids) e.append(k);
	return e;
}
const svgNS = "http://www.w3.org/2000/svg";
function sel(cls, entries, value, onchange) {
	const s = el("select", { class: cls, onchange: () => onchange(s.value) });
	for (const [v, t] of entries) s.append(el("option", { value: v }, t));
	s.value = String(value);
	return s;
}
const label = id => id === REF ? "reference (" + D.reference_samples + " samples)" : D.methods[id].label;
const sources = [[REF, "reference"]].concat(D.methods.map((m, i) => [i, m.label]));

if (!D.images) {
	root.append(el("p", { class: "note" }, D.no_images));
	api.ready = true;
	return;
}

/* ---------------------------------------------------------------- frames: loaded from viewer/NNNN.js */
const frames = new Array(N).fill(null);
const waiting = new Map();
window.aalabFrame = function (f, urls) {
	const done = waiting.get(f);
	if (done) done(urls);
};
function pad4(n) { return String(n).padStart(4, "0"); }
function image(url) {
	if (!url) return Promise.resolve(null);
	const img = new Image();
	img.src = url;
	return img.decode().then(() => img, () => null);
}
/* A frame's images, decoded: {ref, m[], flip[], px: cache of pixel arrays}. */
function loadFrame(f) {
	if (frames[f]) return frames[f].promise;
	const entry = frames[f] = { ready: false };
	entry.promise = new Promise((resolve) => {
		const script = el("script", { src: "viewer/" + pad4(f) + ".js" });
		waiting.set(f, urls => {
			waiting.delete(f);
			Promise.all([image(urls.ref)].concat(urls.m.map(image), urls.flip.map(image))).then(imgs => {
				Object.assign(entry, { ready: true, ref: imgs[0], m: imgs.slice(1, 1 + M), flip: imgs.slice(1 + M),
					px: new Map(), diffs: new Map() });
				script.remove();
				resolve(entry);
			});
		});
		script.onerror = () => {
			entry.failed = true;
			status.textContent = "viewer/" + pad4(f) + ".js could not be loaded: keep the viewer/ folder beside report.html";
			resolve(entry);
		};
		document.head.append(script);
	});
	return entry.promise;
}
function sourceImage(fr, id) { return id === REF ? fr.ref : fr.m[id]; }
/* RGBA bytes of a source (reference or method) or of a FLIP map ("f" + id) in a loaded frame. */
function pixels(fr, key) {
	if (fr.px.has(key)) return fr.px.get(key);
	const img = typeof key === "string" ? fr.flip[+key.slice(1)] : sourceImage(fr, key);
	let data = null;
	if (img) {
		const c = el("canvas");
		c.width = W; c.height = H;
		const g = c.getContext("2d", { willReadFrequently: true });
		g.drawImage(img, 0, 0);
		data = g.getImageData(0, 0, W, H).data;
	}
	fr.px.set(key, data);
	return data;
}

/* ---------------------------------------------------------------- differences */
const luma = (d, i) => 0.2126 * d[i] + 0.7152 * d[i + 1] + 0.0722 * d[i + 2]; /* Rec. 709, as the metrics */
function diffCanvas(fr, id) {
	const key = [id, S.against, S.mode, S.gain, S.threshold].join();
	if (fr.diffs.has(key)) return fr.diffs.get(key);
	const a = pixels(fr, id), b = pixels(fr, S.against);
	const c = el("canvas");
	c.width = W; c.height = H;
	if (a && b) {
		const g = c.getContext("2d");
		const out = g.createImageData(W, H), o = out.data, k = S.gain, limit = S.threshold * 255;
		let over = 0; /* as idiff counts: pixels where any channel differs by more than the threshold */
		for (let i = 0; i < o.length; i += 4) {
			if (Math.abs(a[i] - b[i]) > limit || Math.abs(a[i + 1] - b[i + 1]) > limit || Math.abs(a[i + 2] - b[i + 2]) > limit) over++;
			if (S.mode === "abs") {
				o[i] = Math.abs(a[i] - b[i]) * k;
				o[i + 1] = Math.abs(a[i + 1] - b[i + 1]) * k;
				o[i + 2] = Math.abs(a[i + 2] - b[i + 2]) * k;
			} else if (S.mode === "lum") {
				o[i] = o[i + 1] = o[i + 2] = Math.abs(luma(a, i) - luma(b, i)) * k;
			} else { /* signed luminance: white equal, red brighter than the other, blue darker */
				const v = Math.max(-1, Math.min(1, (luma(a, i) - luma(b, i)) * k / 255));
				o[i] = v < 0 ? 255 * (1 + v) : 255;
				o[i + 1] = 255 * (1 - Math.abs(v));
				o[i + 2] = v > 0 ? 255 * (1 - v) : 255;
			}
			o[i + 3] = 255;
		}
		g.putImageData(out, 0, 0);
		c.over = over;
	}
	fr.diffs.set(key, c);
	return c;
}
const magma = new Map();
for (let i = 0; i < 256; i++) magma.set(parseInt(D.magma.substr(6 * i, 6), 16), i);
/* FLIP value of a map pixel: the map stores index int(255 v + 0.5) of magma, so v to within 1/510. */
function flipValue(d, i) {
	const idx = magma.get(d[i] << 16 | d[i + 1] << 8 | d[i + 2]);
	return idx === undefined ? NaN : idx / 255;
}
const linear = c => { c /= 255; return c <= 0.04045 ? c / 12.92 : Math.pow((c + 0.055) / 1.055, 2.4); };

/* ---------------------------------------------------------------- layout */
const status = el("span", { class: "vw-status" });
const slider = el("input", { type: "range", min: 0, max: Math.max(0, N - 1), value: 0, step: 1, class: "vw-slider",
	"aria-label": "frame", oninput: () => setFrame(+slider.value) });
const frameText = el("span", { class: "vw-frame" });
const playButton = el("button", { type: "button", class: "vw-play", onclick: () => play(!S.playing) }, "\u25b6 play");
const fpsInput = el("input", { type: "number", min: 1, max: 240, value: S.fps, class: "vw-fps", "aria-label": "fps",
	onchange: () => { S.fps = Math.max(1, Math.min(240, +fpsInput.value || D.fps)); } });
const zoomButtons = ZOOMS.map(z => el("button", { type: "button", "data-zoom": z, onclick: () => setZoom(z) }, z + "\u00d7"));
const bar1 = el("div", { class: "vw-bar" },
	el("button", { type: "button", onclick: () => setFrame(S.frame - 1), title: "previous frame (\u2190)" }, "\u25c0"),
	playButton,
	el("button", { type: "button", onclick: () => setFrame(S.frame + 1), title: "next frame (\u2192)" }, "\u25b6\u2758"),
	slider, frameText, el("label", {}, "fps ", fpsInput), status);
const modeSel = sel("vw-mode", [["abs", "|difference| RGB"], ["lum", "|difference| luminance"], ["signed", "signed luminance"]],
	S.mode, v => { S.mode = v; redraw(); });
const gainSel = sel("vw-gain", [1, 2, 4, 8, 16, 32, 64].map(g => [g, "gain \u00d7" + g]), S.gain, v => { S.gain = +v; redraw(); });
const againstSel = sel("vw-against", sources.map(([i, t]) => [i, "against " + t]), S.against,
	v => { S.against = +v; redraw(); });
const thresholdInput = el("input", { type: "number", min: 0, max: 1, step: 0.001, value: S.threshold, class: "vw-threshold",
	"aria-label": "threshold", title: "count pixels where any channel differs by more than this (0..1 of full scale), as idiff does",
	onchange: () => { S.threshold = Math.max(0, Math.min(1, +thresholdInput.value || 0)); redraw(); } });
const aSel = sel("vw-a", sources, S.a, v => { S.a = +v; redraw(); });
const bSel = sel("vw-b", sources, S.b, v => { S.b = +v; redraw(); });
const bar2 = el("div", { class: "vw-bar" }, el("span", { class: "vw-k" }, "zoom"), ...zoomButtons,
	el("span", { class: "vw-k" }, "difference"), modeSel, gainSel, againstSel,
	el("label", {}, "over ", thresholdInput),
	el("span", { class: "vw-k" }, "A"), aSel, el("span", { class: "vw-k" }, "B"), bSel,
	el("button", { type: "button", class: "vw-flip", onclick: () => flip(), title: "show A or B (key F)" }, "flip A/B (F)"));
const help = el("p", { class: "vw-help" }, "Wheel or the buttons zoom (nearest neighbour) and drag pans, in every pane at once; " +
	"F flips the large pane between A and B; \u2190 \u2192 step frames, space plays; the inspector shows the pixel under the cursor. " +
	"Differences are of the 8-bit sRGB values, times the gain.");

const panes = [];
function pane(kind, id, title) {
	const canvas = el("canvas", { class: "vw-canvas", "data-pane": kind + ":" + id });
	const cap = el("div", { class: "vw-cap" }, title);
	const p = { kind, id, canvas, cap };
	panes.push(p);
	attachInput(canvas);
	return el("figure", { class: "vw-pane vw-" + kind }, canvas, cap);
}
const abPane = pane("ab", 0, "");
const abCap = panes[0].cap;
const inspector = el("table", { class: "vw-inspector" });
const inspectorHead = el("div", { class: "vw-k" }, "pixel inspector: move the cursor over a pane");
const chart = document.createElementNS(svgNS, "svg");
chart.setAttribute("class", "vw-chart");
chart.setAttribute("viewBox", "0 0 420 170");
chart.addEventListener("click", ev => chartClick(ev));
const side = el("div", { class: "vw-side" }, inspectorHead, inspector,
	el("div", { class: "vw-k" }, "PSNR per frame (click to pick the frame)"), chart,
	el("ul", { class: "vw-legend" }, ...D.methods.map(m => el("li", {},
		el("span", { class: "vw-swatch", style: "background:" + m.color }), m.label))));
const grid = el("div", { class: "vw-grid" },
	el("div", { class: "vw-h" }, "image"), el("div", { class: "vw-h vw-hd" }, "difference"), el("div", { class: "vw-h" }, "FLIP error map"));
grid.append(pane("img", REF, label(REF)), el("div", { class: "vw-hole" }), el("div", { class: "vw-hole" }));
D.methods.forEach((m, i) => grid.append(pane("img", i, m.label), pane("diff", i, ""), pane("flip", i, m.label + " FLIP")));
const histogram = el("canvas", { class: "vw-hist", width: 720, height: 200 });
const histCap = el("div", { class: "vw-cap" });
const regions = el("div", { class: "vw-regions" });
root.append(bar1, bar2, help, el("div", { class: "vw-top" }, abPane, side), grid,
	el("figure", { class: "vw-histfig" }, histogram, histCap), regions);

/* Pane sizes: each image pixel one CSS pixel at 1x; panes no wider than a third of the page. */
function layout() {
	const avail = Math.max(200, root.clientWidth);
	const small = Math.min(W, Math.floor((avail - 24) / 3)), big = Math.min(W * 2, Math.floor(avail * 0.62));
	for (const p of panes) {
		const w = p.kind === "ab" ? big : small, h = Math.max(32, Math.round(w * H / W));
		const dpr = window.devicePixelRatio || 1;
		p.cssW = w; p.cssH = h;
		p.canvas.style.width = w + "px"; p.canvas.style.height = h + "px";
		p.canvas.width = Math.round(w * dpr); p.canvas.height = Math.round(h * dpr);
	}
	redraw();
}
window.addEventListener("resize", layout);

/* ---------------------------------------------------------------- view: zoom, pan, cursor */
/* Top-left of the image in a pane's CSS pixels: whole pixels, so every image pixel is zoom x zoom. */
function origin(p) {
	return [Math.round(p.cssW / 2 - S.cx * S.zoom), Math.round(p.cssH / 2 - S.cy * S.zoom)];
}
function view() {
	const p = panes[0];
	const [ox, oy] = p && p.cssW ? origin(p) : [0, 0];
	return { ox, oy, paneW: p ? p.cssW : 0, paneH: p ? p.cssH : 0 };
}
function setZoom(z, p, mx, my) {
	z = Math.max(1, Math.min(32, z));
	if (p) { /* keep the image point under the cursor where it is */
		const [ox, oy] = origin(p);
		const ix = (mx - ox) / S.zoom, iy = (my - oy) / S.zoom;
		S.cx = ix - (mx - p.cssW / 2) / z;
		S.cy = iy - (my - p.cssH / 2) / z;
	}
	S.zoom = z;
	clampCenter();
	redraw();
}
function clampCenter() {
	S.cx = Math.max(0, Math.min(W, S.cx));
	S.cy = Math.max(0, Math.min(H, S.cy));
}
function attachInput(canvas) {
	let drag = null;
	const paneOf = () => panes.find(p => p.canvas === canvas);
	canvas.addEventListener("mousedown", ev => { drag = [ev.clientX, ev.clientY, S.cx, S.cy]; ev.preventDefault(); });
	window.addEventListener("mouseup", () => { drag = null; });
	canvas.addEventListener("mousemove", ev => {
		const p = paneOf(), r = canvas.getBoundingClientRect(), [ox, oy] = origin(p);
		if (drag && ev.buttons) {
			S.cx = drag[2] - (ev.clientX - drag[0]) / S.zoom;
			S.cy = drag[3] - (ev.clientY - drag[1]) / S.zoom;
			clampCenter();
		}
		S.hover = true;
		S.px = Math.floor((ev.clientX - r.left - ox) / S.zoom);
		S.py = Math.floor((ev.clientY - r.top - oy) / S.zoom);
		redraw();
	});
	canvas.addEventListener("mouseleave", () => { S.hover = false; redraw(); });
	canvas.addEventListener("wheel", ev => {
		ev.preventDefault();
		const r = canvas.getBoundingClientRect();
		const i = ZOOMS.indexOf(S.zoom), next = ev.deltaY < 0 ? ZOOMS[Math.min(ZOOMS.length - 1, i + 1)] : ZOOMS[Math.max(0, i - 1)];
		setZoom(next, paneOf(), ev.clientX - r.left, ev.clientY - r.top);
	}, { passive: false });
}
function flip() { S.showB = !S.showB; redraw(); }
document.addEventListener("keydown", ev => {
	const t = ev.target && ev.target.tagName;
	if (t === "INPUT" && ev.target.type !== "range" || t === "SELECT" || t === "TEXTAREA" || ev.ctrlKey || ev.metaKey || ev.altKey) return;
	if (ev.key === "f" || ev.key === "F") flip();
	else if (ev.key === " ") play(!S.playing);
	else if (ev.key === "ArrowLeft") setFrame(S.frame - 1);
	else if (ev.key === "ArrowRight") setFrame(S.frame + 1);
	else if (ev.key === "+" || ev.key === "=") setZoom(S.zoom * 2);
	else if (ev.key === "-") setZoom(S.zoom / 2);
	else return;
	ev.preventDefault();
});

/* ---------------------------------------------------------------- frames: scrub and play */
function setFrame(f) {
	S.frame = ((f % N) + N) % N;
	slider.value = S.frame;
	loadFrame(S.frame).then(() => redraw());
	redraw();
}
let playTimer = 0;
function play(on) {
	S.playing = on && N > 1;
	playButton.textContent = S.playing ? "\u275a\u275a pause" : "\u25b6 play";
	cancelAnimationFrame(playTimer);
	if (!S.playing) return redraw();
	for (let f = 0; f < N; f++) loadFrame((S.frame + f) % N); /* all of them: playback must not wait */
	let last = performance.now();
	S.playedFrames = 0;
	S.playStart = last;
	const tick = now => {
		if (!S.playing) return;
		const next = (S.frame + 1) % N;
		if (now - last >= 1000 / S.fps && frames[next] && frames[next].ready) {
			last = now - Math.min(1000 / S.fps, now - last - 1000 / S.fps);
			setFrame(next);
			S.playedFrames++;
			S.measuredFps = S.playedFrames * 1000 / (now - S.playStart);
		}
		playTimer = requestAnimationFrame(tick);
	};
	playTimer = requestAnimationFrame(tick);
}

/* ---------------------------------------------------------------- drawing */
let pending = 0;
function redraw() {
	if (!pending) pending = requestAnimationFrame(() => { pending = 0; draw(); });
}
function paneSource(fr, p) {
	if (p.kind === "ab") return sourceImage(fr, S.showB ? S.b : S.a);
	if (p.kind === "img") return sourceImage(fr, p.id);
	if (p.kind === "flip") return fr.flip[p.id];
	return diffCanvas(fr, p.id);
}
function draw() {
	const t0 = performance.now();
	drawPanes();
	S.drawMs = performance.now() - t0; /* what a shown frame costs: playback cannot beat 1000 / drawMs */
}
function drawPanes() {
	const fr = frames[S.frame];
	if (fr && fr.ready) {
		if (S.shown < 0) api.readyAt = performance.now(); /* the first frame on screen, ms after navigation */
		S.shown = S.frame;
	}
	const shown = S.shown >= 0 ? frames[S.shown] : null;
	frameText.textContent = "frame " + D.frames[S.frame] + " (" + (S.frame + 1) + " of " + N + ")" +
		(S.shown !== S.frame ? ", loading\u2026" : "") + (S.playing && S.measuredFps ? ", playing at " + S.measuredFps.toFixed(1) + " fps" : "");
	for (const b of zoomButtons) b.classList.toggle("on", +b.dataset.zoom === S.zoom);
	abCap.textContent = (S.showB ? "B: " : "A: ") + label(S.showB ? S.b : S.a) + " \u2014 press F for " +
		(S.showB ? "A: " + label(S.a) : "B: " + label(S.b));
	abCap.dataset.showing = S.showB ? "B" : "A";
	for (const p of panes) {
		if (p.kind === "diff") {
			const d = shown && diffCanvas(shown, p.id);
			p.cap.textContent = D.methods[p.id].label + " \u2212 " + (S.against === REF ? "reference" : D.methods[S.against].label) +
				" (" + modeSel.selectedOptions[0].textContent + ", \u00d7" + S.gain + ")" +
				(d && d.over !== undefined ? "; " + d.over + " px (" + (100 * d.over / (W * H)).toFixed(2) + "%) over " + S.threshold : "");
			p.cap.dataset.over = d && d.over !== undefined ? d.over : "";
		}
		const g = p.canvas.getContext("2d");
		const dpr = p.canvas.width / p.cssW;
		g.setTransform(1, 0, 0, 1, 0, 0);
		g.fillStyle = "#1e293b";
		g.fillRect(0, 0, p.canvas.width, p.canvas.height);
		const src = shown && paneSource(shown, p);
		if (!src) continue;
		const [ox, oy] = origin(p);
		g.setTransform(dpr * S.zoom, 0, 0, dpr * S.zoom, dpr * ox, dpr * oy);
		g.imageSmoothingEnabled = false;
		g.drawImage(src, 0, 0);
		if (S.px >= 0 && S.py >= 0 && S.px < W && S.py < H && S.zoom >= 4 && S.hover) { /* the pixel under the cursor */
			g.lineWidth = 1 / S.zoom;
			g.strokeStyle = "#22d3ee";
			g.strokeRect(S.px, S.py, 1, 1);
		}
	}
	if (shown) {
		if (S.hover || !S.playing) inspect(shown);
		if (!S.playing) drawHistogram(shown); /* per frame it would cost playback a third of its rate */
	}
	drawChart();
}
const fmt = (v, d) => Number.isFinite(v) ? v.toFixed(d) : "\u2014";
function inspect(fr) {
	const x = S.px, y = S.py;
	if (x < 0 || y < 0 || x >= W || y >= H) return;
	inspectorHead.textContent = "pixel (" + x + ", " + y + "), frame " + D.frames[S.shown];
	const i = (y * W + x) * 4, rows = [el("tr", {}, el("th", {}, ""), el("th", {}, "sRGB 8-bit"), el("th", {}, "linear"),
		el("th", {}, "\u2212 " + (S.against === REF ? "ref" : D.methods[S.against].label)), el("th", {}, "FLIP"))];
	const b = pixels(fr, S.against);
	for (const [id, name] of sources) {
		const d = pixels(fr, id);
		if (!d) continue;
		const f = id === REF ? null : pixels(fr, "f" + id);
		rows.push(el("tr", { "data-source": id }, el("td", {}, name),
			el("td", { class: "vw-srgb" }, d[i] + " " + d[i + 1] + " " + d[i + 2]),
			el("td", { class: "vw-lin" }, [0, 1, 2].map(c => linear(d[i + c]).toFixed(4)).join(" ")),
			el("td", { class: "vw-diff" }, b ? [0, 1, 2].map(c => d[i + c] - b[i + c]).join(" ") : ""),
			el("td", { class: "vw-flipv" }, f ? fmt(flipValue(f, i), 3) : "")));
	}
	inspector.replaceChildren(...rows);
}
function drawChart() {
	const L = 40, R = 410, T = 10, B = 140;
	let lo = Infinity, hi = -Infinity;
	for (const m of D.methods) for (const v of m.psnr) if (v !== null) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
	if (!Number.isFinite(lo)) { lo = 0; hi = 50; }
	lo = Math.floor(lo - 1); hi = Math.ceil(hi + 1);
	const x = f => N > 1 ? L + (R - L) * f / (N - 1) : (L + R) / 2;
	/* frames identical to the reference (infinite PSNR) sit on a strip above the scale, named only when
	 * there are any: the top of the scale is a finite PSNR, never "identical" */
	const anyIdentical = D.methods.some(m => m.identical.some(i => i));
	const top = anyIdentical ? T + 14 : T;
	const y = v => v === null ? T + 4 : top + 8 + (B - top - 8) * (hi - v) / (hi - lo);
	chart.dataset.left = L; chart.dataset.right = R;
	let s = `<rect x="${L}" y="${T}" width="${R - L}" height="${B - T}" fill="#fff" stroke="#cbd5e1"/>` +
		`<text x="${L - 4}" y="${top + 12}" text-anchor="end" class="t">${hi}</text><text x="${L - 4}" y="${B}" text-anchor="end" class="t">${lo}</text>` +
		(anyIdentical ? `<line x1="${L}" x2="${R}" y1="${top}" y2="${top}" stroke="#94a3b8" stroke-dasharray="3 2"/>` +
			`<text x="${L + 4}" y="${T + 8}" class="t vw-identical">identical to the reference</text>` : "") +
		`<text x="${L}" y="${B + 14}" class="t">${D.frames[0]}</text><text x="${R}" y="${B + 14}" text-anchor="end" class="t">${D.frames[N - 1]}</text>` +
		`<text x="${(L + R) / 2}" y="${B + 28}" text-anchor="middle" class="t">frame \u00b7 PSNR dB (mean over the frame; higher is closer)</text>`;
	D.methods.forEach(m => {
		s += `<polyline fill="none" stroke="${m.color}" stroke-width="1.5" points="${m.psnr.map((v, f) =>
			x(f).toFixed(1) + "," + y(m.identical[f] ? null : v).toFixed(1)).join(" ")}"/>`;
	});
	s += `<line class="vw-cursor" x1="${x(S.frame)}" x2="${x(S.frame)}" y1="${T}" y2="${B}" stroke="#0f172a" stroke-dasharray="3 2"/>`;
	chart.innerHTML = s;
}
function chartClick(ev) {
	const r = chart.getBoundingClientRect(), vx = (ev.clientX - r.left) * 420 / r.width;
	const L = 40, R = 410;
	setFrame(N > 1 ? Math.round(Math.max(0, Math.min(1, (vx - L) / (R - L))) * (N - 1)) : 0);
}
/* FLIP histogram of A (against the reference) in the shown frame, weighted as NVIDIA's tool weights it:
 * each bin's pixel count times its error, so the bins that make up the mean stand out. */
function drawHistogram(fr) {
	const g = histogram.getContext("2d"), bins = 100, hist = new Float64Array(bins);
	g.clearRect(0, 0, histogram.width, histogram.height);
	const id = S.a === REF ? 0 : S.a, f = M ? pixels(fr, "f" + id) : null;
	if (!f) { histCap.textContent = "FLIP histogram: no FLIP map"; return; }
	let sum = 0, n = 0;
	for (let i = 0; i < f.length; i += 4) {
		const v = flipValue(f, i);
		if (!Number.isFinite(v)) continue;
		hist[Math.min(bins - 1, Math.floor(v * bins))] += v;
		sum += v; n++;
	}
	const top = Math.max(...hist) || 1, L = 40, B = histogram.height - 24, w = (histogram.width - L - 10) / bins;
	g.fillStyle = "#64748b"; g.font = "11px sans-serif";
	g.fillText("0", L, B + 14); g.fillText("1", L + bins * w - 6, B + 14); g.fillText("FLIP error", L + bins * w / 2 - 24, B + 14);
	for (let b = 0; b < bins; b++) {
		const h = (B - 10) * hist[b] / top;
		g.fillStyle = "#" + D.magma.substr(6 * Math.min(255, Math.round((b + 0.5) * 255 / bins)), 6);
		g.fillRect(L + b * w, B - h, Math.max(1, w - 1), h);
	}
	const mean = n ? sum / n : NaN;
	g.strokeStyle = "#dc2626"; g.beginPath(); g.moveTo(L + mean * bins * w, 8); g.lineTo(L + mean * bins * w, B); g.stroke();
	g.strokeStyle = "#cbd5e1"; g.strokeRect(L, 8, bins * w, B - 8);
	histCap.textContent = "FLIP histogram of " + label(id) + " against the reference, frame " + D.frames[S.shown] +
		": pixel count \u00d7 error per bin (weighted, as NVIDIA's FLIP tool draws it); red line: mean " + fmt(mean, 4);
}

/* ---------------------------------------------------------------- worst regions first */
/* Each region (report_regions.c: the tiles with the most FLIP error over every method and frame) as
 * close-ups at 8x, the reference and every method side by side, in the frame where it is worst; a
 * click shows that place and frame in the panes above at 8x. */
/* A crop from its data: URL in the page (report_regions.c), at 8x; without one, a note in the square
 * until the frame's script has loaded, rather than an empty square. */
function drawCrop(c, url, g) {
	const gc = c.getContext("2d");
	gc.imageSmoothingEnabled = false;
	if (!url) {
		gc.fillStyle = "#e2e8f0"; gc.fillRect(0, 0, c.width, c.height);
		gc.fillStyle = "#475569"; gc.font = "12px sans-serif";
		gc.fillText("loading frame " + D.frames[g.ordinal] + "\u2026", 6, 18);
		return;
	}
	const img = new Image();
	img.onload = () => gc.drawImage(img, 0, 0, g.w * 8, g.h * 8);
	img.src = url;
}
function drawRegions() {
	if (!D.regions.length) return;
	regions.append(el("div", { class: "vw-k" }, "worst regions first: where the methods differ most from the reference " +
		"(FLIP summed over every method and frame), at 8× in the frame where each is worst; click one to look around it"));
	D.regions.forEach((g, k) => {
		const row = el("div", { class: "vw-region", "data-region": k, title: "show it above at 8×", onclick: () => {
			S.zoom = 8; S.cx = g.x + g.w / 2; S.cy = g.y + g.h / 2;
			setFrame(g.ordinal);
			root.scrollIntoView();
		} });
		row.append(el("div", { class: "vw-cap" }, "#" + (k + 1) + ": frame " + D.frames[g.ordinal] + ", pixels " + g.x + "–" +
			(g.x + g.w - 1) + " × " + g.y + "–" + (g.y + g.h - 1) + ", mean FLIP " + g.flip_mean.toFixed(3)));
		const crops = sources.map(([id, name], k) => {
			const c = el("canvas", { width: g.w * 8, height: g.h * 8, class: "vw-crop" });
			row.append(el("figure", { class: "vw-pane" }, c, el("div", { class: "vw-cap" }, name)));
			drawCrop(c, g.crops && g.crops[k], g);
			return [id, c];
		});
		regions.append(row);
		if (g.crops && g.crops.every(u => u)) return; /* drawn from the page's own data */
		loadFrame(g.ordinal).then(fr => {
			if (!fr.ready) return;
			for (const [id, c] of crops) {
				const img = sourceImage(fr, id), gc = c.getContext("2d");
				gc.imageSmoothingEnabled = false;
				if (img) gc.drawImage(img, g.x, g.y, g.w, g.h, 0, 0, g.w * 8, g.h * 8);
			}
		});
	});
}

layout();
setFrame(0);
loadFrame(0).then(() => { api.ready = true; redraw(); drawRegions(); });
})();
