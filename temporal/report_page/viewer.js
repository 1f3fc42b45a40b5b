// kdop taa's report.html (temporal/taa_report_page.h): the sortable table and the frame viewer.
// Plain JavaScript, no library and no network: everything it shows is in the page's data
// (<script id="kdop-data">) and the PNGs beside it. The viewer's state lives in the URL fragment
// (#sequence=S (or SCENE/S)&frame=N&a=V&b=V&mode=side|flip&shown=a|b&map=frame|overlay|map&zoom=Z), so a state
// can be linked to, and is what the tests drive it with. Without one it opens on the first sequence
// measured for ghosting, its best variant against its worst, at the worst one's worst frame.
"use strict";

(function () {
  const data = JSON.parse(document.getElementById("kdop-data").textContent);

  // Images that fail to load are counted on <body data-broken-images>: what the tests read.
  document.body.dataset.brokenImages = "0";
  document.addEventListener("error", (e) => {
    if (e.target.tagName !== "IMG") return;
    document.body.dataset.brokenImages = String(Number(document.body.dataset.brokenImages) + 1);
    e.target.title = "missing: " + e.target.getAttribute("src");
  }, true);

  // --- The table: a click on a header sorts by that column (numbers as numbers, empty last). ---
  for (const table of document.querySelectorAll("table.results")) {
    const headers = table.querySelectorAll("th");
    headers.forEach((th, column) => {
      th.addEventListener("click", () => {
        const ascending = th.getAttribute("aria-sort") !== "ascending";
        headers.forEach((h) => h.removeAttribute("aria-sort"));
        th.setAttribute("aria-sort", ascending ? "ascending" : "descending");
        const body = table.tBodies[0];
        const rows = Array.from(body.rows);
        const key = (row) => {
          const cell = row.cells[column];
          return cell.dataset.value !== undefined ? cell.dataset.value : cell.textContent;
        };
        rows.sort((x, y) => {
          const a = key(x), b = key(y);
          if (a === "" || b === "") return (a === "") - (b === "");
          const na = Number(a), nb = Number(b);
          const order = !isNaN(na) && !isNaN(nb) ? na - nb : a.localeCompare(b);
          return ascending ? order : -order;
        });
        for (const row of rows) body.appendChild(row);
      });
    });
  }

  // --- The frame viewer. ---
  const viewer = document.getElementById("viewer");
  if (!viewer || data.viewer.length === 0) return;
  const $ = (id) => document.getElementById(id);
  const variants = data.variants;
  // Small frames start magnified, so two side by side fill about the page's width.
  const fitting = (s) => {
    const zoom = Math.floor(660 / s.width);
    return zoom >= 4 ? 4 : zoom >= 2 ? 2 : 1;
  };
  const state = { sequence: 0, frame: 0, a: 0, b: Math.min(1, variants.length - 1), mode: "side", shown: "a",
                  map: "frame", zoom: fitting(data.viewer[0]) };
  // "truth" is the reference or aliased frame; a variant by its name.
  const choices = () => ["truth"].concat(variants);

  function path(sequence, frame, image, map) {
    const seg = encodeURIComponent;
    return "viewer/" + seg(sequence.scene) + "/" + seg(sequence.name) + "/" + String(frame).padStart(4, "0") + "/" +
      (map ? "flip/" : "") + seg(image) + ".png";
  }

  function option(select, value, text) {
    const o = document.createElement("option");
    o.value = value;
    o.textContent = text;
    select.appendChild(o);
  }

  // A sequence by its name, or, for one of a scene's two, "<scene>/<sequence>".
  const label = (s) => (s.scene === s.name ? s.name : s.scene + "/" + s.name);
  data.viewer.forEach((s, i) => option($("sequence"), i, label(s)));
  for (const select of [$("variant-a"), $("variant-b")]) choices().forEach((name, i) => option(select, i - 1, name));

  function figureText(sequence, frameIndex, v) {
    if (v < 0) return sequence.truth + " frame";
    const figure = sequence.figures[frameIndex][v];
    return (figure === null ? "no " + sequence.figure : sequence.figure + " " + figure.toFixed(4)) + " on this frame";
  }

  // One view: the frame (or truth) with its FLIP map over it or instead of it.
  function view(slot, v) {
    const sequence = data.viewer[state.sequence];
    const frame = sequence.frames[state.frame];
    const name = v < 0 ? sequence.truth : variants[v];
    const figure = document.createElement("figure");
    figure.className = "view";
    figure.id = "view-" + slot;
    const stack = document.createElement("div");
    stack.className = "stack";
    stack.dataset.map = v < 0 ? "frame" : state.map;
    const image = document.createElement("img");
    image.className = "frame";
    image.alt = name + ", frame " + frame;
    image.src = path(sequence, frame, name, false);
    stack.appendChild(image);
    if (v >= 0 && sequence.figures[state.frame][v] !== null) {
      const map = document.createElement("img");
      map.className = "map";
      map.alt = "FLIP map of " + name + ", frame " + frame;
      map.src = path(sequence, frame, name, true);
      stack.appendChild(map);
    }
    figure.appendChild(stack);
    const caption = document.createElement("figcaption");
    caption.textContent = name + ": " + figureText(sequence, state.frame, v);
    figure.appendChild(caption);
    return figure;
  }

  function render() {
    const sequence = data.viewer[state.sequence];
    state.frame = Math.max(0, Math.min(state.frame, sequence.frames.length - 1));
    // A sequence that does not upscale has no spatial-only upscale, the last variant: offer only
    // the variants that resolved it.
    state.a = Math.min(state.a, sequence.variants - 1);
    state.b = Math.min(state.b, sequence.variants - 1);
    for (const select of [$("variant-a"), $("variant-b")])
      for (const o of select.options) o.disabled = Number(o.value) >= sequence.variants;
    $("sequence").value = state.sequence;
    $("frame-slider").max = sequence.frames.length - 1;
    $("frame-slider").value = state.frame;
    $("frame-label").textContent = "frame " + sequence.frames[state.frame] + " (" + (state.frame + 1) + " of " +
      sequence.frames.length + " kept)";
    $("variant-a").value = state.a;
    $("variant-b").value = state.b;
    $("mode").value = state.mode;
    $("map").value = state.map;
    $("zoom").value = state.zoom;
    $("map-caption").textContent = "FLIP maps: " + sequence.map + " (black: no difference; yellow: 1).";
    const views = $("views");
    views.replaceChildren();
    if (state.mode === "side") {
      views.appendChild(view("a", state.a));
      views.appendChild(view("b", state.b));
    } else {
      views.appendChild(view(state.shown, state.shown === "a" ? state.a : state.b));
    }
    const width = sequence.width * state.zoom;
    views.style.setProperty("--shown-width", width + "px");
    const worst = $("worst");
    worst.replaceChildren();
    sequence.worst.forEach((frame, v) => {
      if (frame === null) return;
      const button = document.createElement("button");
      button.textContent = variants[v] + ": frame " + frame;
      button.dataset.variant = variants[v];
      if (frame === sequence.frames[state.frame]) button.className = "here";
      button.addEventListener("click", () => {
        state.frame = sequence.frames.indexOf(frame);
        if (state.a !== v && state.b !== v) state.b = v;
        update();
      });
      worst.appendChild(button);
    });
    viewer.dataset.state = fragment();
  }

  function fragment() {
    const s = data.viewer[state.sequence];
    const name = (v) => (v < 0 ? "truth" : variants[v]);
    return "sequence=" + encodeURIComponent(label(s)) + "&frame=" + s.frames[state.frame] + "&a=" +
      encodeURIComponent(name(state.a)) + "&b=" + encodeURIComponent(name(state.b)) + "&mode=" + state.mode +
      "&shown=" + state.shown + "&map=" + state.map + "&zoom=" + state.zoom;
  }

  function update() {
    render();
    history.replaceState(null, "", "#" + fragment());
  }

  // Where a sequence opens: the variant with the least mean figure as A, the one with the most as B,
  // at B's worst frame, where the two differ most plainly.
  function openOn(sequenceIndex) {
    const sequence = data.viewer[sequenceIndex];
    const measured = sequence.means.map((m, v) => [m, v]).filter(([m]) => m !== null);
    if (measured.length === 0) return;
    measured.sort((x, y) => x[0] - y[0] || x[1] - y[1]);
    state.a = measured[0][1];
    state.b = measured[measured.length - 1][1];
    if (state.b === state.a) state.b = state.a === 0 ? Math.min(1, variants.length - 1) : 0;
    const frame = sequence.frames.indexOf(sequence.worst[state.b]);
    state.frame = frame >= 0 ? frame : 0;
  }

  function readFragment() {
    const params = new URLSearchParams(location.hash.slice(1));
    const sequence = data.viewer.findIndex((s) => label(s) === params.get("sequence"));
    // Without one named, the first sequence measured for ghosting, the figure the table sorts by.
    const ghosting = data.viewer.findIndex((s) => s.figure === "ghosting");
    state.sequence = sequence >= 0 ? sequence : Math.max(ghosting, 0);
    const frames = data.viewer[state.sequence].frames;
    state.zoom = fitting(data.viewer[state.sequence]);
    openOn(state.sequence);
    $("frame-note").textContent = "";
    if (params.has("frame")) {
      const wanted = Number(params.get("frame"));
      // The kept frame nearest the one asked for, saying so where it is another.
      let best = 0;
      frames.forEach((f, i) => { if (Math.abs(f - wanted) < Math.abs(frames[best] - wanted)) best = i; });
      state.frame = best;
      if (frames[best] !== wanted)
        $("frame-note").textContent = "frame " + params.get("frame") + " was not kept; showing the nearest kept " +
          "frame, " + frames[best] + " (the kept frames: " + frames.join(", ") + ")";
    }
    for (const slot of ["a", "b"])
      if (params.has(slot)) {
        const v = choices().indexOf(params.get(slot));
        if (v >= 0) state[slot] = v - 1;
      }
    if (["side", "flip"].includes(params.get("mode"))) state.mode = params.get("mode");
    if (["a", "b"].includes(params.get("shown"))) state.shown = params.get("shown");
    if (["frame", "overlay", "map"].includes(params.get("map"))) state.map = params.get("map");
    if (["1", "2", "4"].includes(params.get("zoom"))) state.zoom = Number(params.get("zoom"));
  }

  $("sequence").addEventListener("change", (e) => {
    state.sequence = Number(e.target.value);
    openOn(state.sequence);
    state.zoom = fitting(data.viewer[state.sequence]);
    $("frame-note").textContent = "";
    update();
  });
  const clearNote = () => { $("frame-note").textContent = ""; };
  $("frame-slider").addEventListener("input", clearNote);
  $("frame-slider").addEventListener("input", (e) => { state.frame = Number(e.target.value); update(); });
  $("variant-a").addEventListener("change", (e) => { state.a = Number(e.target.value); update(); });
  $("variant-b").addEventListener("change", (e) => { state.b = Number(e.target.value); update(); });
  $("mode").addEventListener("change", (e) => { state.mode = e.target.value; update(); });
  $("map").addEventListener("change", (e) => { state.map = e.target.value; update(); });
  $("zoom").addEventListener("change", (e) => { state.zoom = Number(e.target.value); update(); });
  document.addEventListener("keydown", (e) => {
    if (e.target.tagName === "INPUT" && e.target.type !== "range") return;
    const sequence = data.viewer[state.sequence];
    if (e.key === "f" || e.key === " ") {
      // Flip between the two: in side-by-side mode, the first press starts flipping.
      if (state.mode === "side") state.mode = "flip";
      else state.shown = state.shown === "a" ? "b" : "a";
    } else if (e.key === "m") {
      state.map = { frame: "overlay", overlay: "map", map: "frame" }[state.map];
    } else if (e.key === "ArrowRight" || e.key === ".") {
      state.frame = Math.min(state.frame + 1, sequence.frames.length - 1);
    } else if (e.key === "ArrowLeft" || e.key === ",") {
      state.frame = Math.max(state.frame - 1, 0);
    } else if (e.key === "w") {
      // Each press steps to the next variant's worst frame.
      const worst = sequence.worst.map((f) => sequence.frames.indexOf(f)).filter((i) => i >= 0).sort((x, y) => x - y);
      if (worst.length === 0) return;
      state.frame = worst.find((i) => i > state.frame) ?? worst[0];
    } else {
      return;
    }
    e.preventDefault();
    update();
  });
  window.addEventListener("hashchange", () => { readFragment(); render(); });

  readFragment();
  render();
  // A link to a state shows the viewer, not the top of the page.
  if (new URLSearchParams(location.hash.slice(1)).has("sequence")) viewer.scrollIntoView();
})();
