// refracta.widgets canvas (anywidget ES module): draws the rendered PNG scaled to the canvas and
// the pairs' markers over it, and sends pointer events to Python in image pixels (u right, v down,
// pixel (i, j) centred at (i + 0.5, j + 0.5)), as refracta.Camera uses them.
//
// Model traits: image (PNG bytes), width/height (image pixels of the camera), scale (display
// pixels per image pixel), markers ([{kind, pair, u, v, selected, met}]), spots (hot-spot outlines
// [{spot, footprint, hot, centre: [u, v] | null, rings: [{kind, radius, points: [[u, v] | null]}]}],
// drawn under the markers: 'radius' solid, 'reach' dashed; null points break the line), interactive, cursor,
// level ('preview' | 'full'), generation (counts images; mirrored into data-* attributes so tests
// and scripts can wait for a new image).
// Messages to Python: {event: 'down' | 'move' | 'up', u, v, button, shift, scale} and
// {event: 'wheel', steps} (steps > 0: toward the look-at point).

const COLOURS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                 "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"];  // matplotlib tab10, as plot.edit_report
const SPOT_COLOURS = { hot: "#ff5722", cold: "#29b6f6" };  // warm and cold ground, apart from the pairs' tab10

function render({ model, el }) {
  const canvas = document.createElement("canvas");
  canvas.className = "refracta-canvas";
  canvas.tabIndex = 0;
  el.appendChild(canvas);
  const context = canvas.getContext("2d");
  let bitmap = null;
  let loading = Promise.resolve();

  function resize() {
    const width = model.get("width"), height = model.get("height"), scale = model.get("scale");
    const ratio = window.devicePixelRatio || 1;
    canvas.style.width = `${Math.round(width * scale)}px`;
    canvas.style.height = `${Math.round(height * scale)}px`;
    canvas.width = Math.round(width * scale * ratio);
    canvas.height = Math.round(height * scale * ratio);
    canvas.style.cursor = model.get("cursor");
    draw();
  }

  function toCanvas(u, v) {
    return [u / model.get("width") * canvas.width, v / model.get("height") * canvas.height];
  }

  function drawMarker(marker, ratio) {
    const [x, y] = toCanvas(marker.u, marker.v);
    const colour = marker.kind === "pending" ? "#ffffff" : COLOURS[marker.pair % COLOURS.length];
    const r = (marker.selected ? 6 : 5) * ratio;
    context.lineWidth = (marker.selected ? 2.5 : 1.5) * ratio;
    context.strokeStyle = "rgba(0, 0, 0, 0.7)";
    context.fillStyle = colour;
    context.beginPath();
    if (marker.kind === "destination") {
      context.rect(x - r, y - r, 2 * r, 2 * r);     // destination: a square with a cross
      context.moveTo(x - 2 * r, y); context.lineTo(x + 2 * r, y);
      context.moveTo(x, y - 2 * r); context.lineTo(x, y + 2 * r);
      context.stroke();
      context.strokeStyle = colour;
      context.lineWidth = 1.2 * ratio;
      context.stroke();
    } else {
      context.arc(x, y, r, 0, 2 * Math.PI);          // source: a dot; pending: a hollow ring
      if (marker.kind === "source") context.fill();
      context.stroke();
    }
    if (marker.met === false && marker.kind === "destination") {
      context.beginPath();
      context.strokeStyle = "#ff2020";
      context.setLineDash([3 * ratio, 2 * ratio]);
      context.arc(x, y, 2.6 * r, 0, 2 * Math.PI);    // a pair the solve could not meet
      context.stroke();
      context.setLineDash([]);
    }
  }

  function drawSpot(spot, ratio) {
    const colour = spot.hot ? SPOT_COLOURS.hot : SPOT_COLOURS.cold;
    for (const ring of spot.rings) {
      context.beginPath();
      let drawing = false;
      for (const point of ring.points) {
        if (point === null) { drawing = false; continue; }   // behind the camera: the line breaks
        const [x, y] = toCanvas(point[0], point[1]);
        if (drawing) context.lineTo(x, y); else context.moveTo(x, y);
        drawing = true;
      }
      context.setLineDash(ring.kind === "reach" ? [5 * ratio, 4 * ratio] : []);
      context.lineWidth = (ring.kind === "reach" ? 1.0 : 1.8) * ratio;
      context.strokeStyle = "rgba(0, 0, 0, 0.5)";               // a dark halo, then the colour
      context.lineWidth += 1.5 * ratio;
      context.stroke();
      context.lineWidth -= 1.5 * ratio;
      context.strokeStyle = colour;
      context.stroke();
      context.setLineDash([]);
    }
    if (spot.centre) {
      const [x, y] = toCanvas(spot.centre[0], spot.centre[1]);
      const r = 4 * ratio;
      context.beginPath();
      context.moveTo(x - r, y); context.lineTo(x + r, y);
      context.moveTo(x, y - r); context.lineTo(x, y + r);
      context.lineWidth = 1.5 * ratio;
      context.strokeStyle = colour;
      context.stroke();
      context.font = `bold ${11 * ratio}px sans-serif`;
      context.fillStyle = colour;
      context.fillText(`#${spot.spot}`, x + r + 2 * ratio, y - r);
    }
  }

  function draw() {
    const ratio = window.devicePixelRatio || 1;
    context.fillStyle = "#202020";
    context.fillRect(0, 0, canvas.width, canvas.height);
    if (bitmap) {
      context.imageSmoothingEnabled = true;
      context.drawImage(bitmap, 0, 0, canvas.width, canvas.height);
    }
    for (const spot of model.get("spots") || []) drawSpot(spot, ratio);
    const markers = model.get("markers") || [];
    const byPair = {};
    for (const marker of markers) {
      if (marker.pair >= 0) (byPair[marker.pair] = byPair[marker.pair] || {})[marker.kind] = marker;
    }
    for (const pair of Object.values(byPair)) {      // source -> destination links
      if (!pair.source || !pair.destination) continue;
      const [x0, y0] = toCanvas(pair.source.u, pair.source.v), [x1, y1] = toCanvas(pair.destination.u, pair.destination.v);
      context.beginPath();
      context.setLineDash([4 * ratio, 3 * ratio]);
      context.lineWidth = 1.2 * ratio;
      context.strokeStyle = COLOURS[pair.source.pair % COLOURS.length];
      context.moveTo(x0, y0);
      context.lineTo(x1, y1);
      context.stroke();
      context.setLineDash([]);
    }
    for (const marker of markers) drawMarker(marker, ratio);
  }

  async function loadImage() {
    const data = model.get("image");
    const generation = model.get("generation"), level = model.get("level");
    if (!data || data.byteLength === 0) {
      bitmap = null;
    } else {
      const blob = new Blob([data], { type: "image/png" });
      bitmap = await createImageBitmap(blob);
    }
    draw();
    canvas.dataset.level = level;
    canvas.dataset.generation = String(generation);
  }

  function queueImage() { loading = loading.then(loadImage, loadImage); }

  function position(event) {
    const rect = canvas.getBoundingClientRect();
    return {
      u: (event.clientX - rect.left) / rect.width * model.get("width"),
      v: (event.clientY - rect.top) / rect.height * model.get("height"),
      scale: rect.width / model.get("width"),
    };
  }

  let pressed = false, queuedMove = null;
  function send(event, extra) { model.send(Object.assign({ event }, extra)); }

  function onDown(event) {
    if (!model.get("interactive")) return;
    event.preventDefault();
    canvas.focus();
    pressed = true;
    canvas.setPointerCapture(event.pointerId);
    send("down", Object.assign(position(event), { button: event.button, shift: event.shiftKey }));
  }
  function onMove(event) {
    if (!pressed) return;
    const first = queuedMove === null;
    queuedMove = position(event);
    if (first) {                                   // at most one move message per frame
      // onUp may have sent and cleared it before this frame: then there is nothing left to send.
      requestAnimationFrame(() => { if (queuedMove !== null) send("move", queuedMove); queuedMove = null; });
    }
  }
  function onUp(event) {
    if (!pressed) return;
    pressed = false;
    if (queuedMove !== null) { send("move", queuedMove); queuedMove = null; }
    send("up", position(event));
  }
  function onWheel(event) {
    if (!model.get("interactive")) return;
    event.preventDefault();
    const unit = event.deltaMode === 0 ? 100 : event.deltaMode === 1 ? 3 : 1;  // pixels, lines, pages
    send("wheel", { steps: -event.deltaY / unit });
  }
  const noMenu = (event) => event.preventDefault();

  canvas.addEventListener("pointerdown", onDown);
  canvas.addEventListener("pointermove", onMove);
  canvas.addEventListener("pointerup", onUp);
  canvas.addEventListener("pointercancel", onUp);
  canvas.addEventListener("wheel", onWheel, { passive: false });
  canvas.addEventListener("contextmenu", noMenu);
  model.on("change:image", queueImage);
  model.on("change:markers", draw);
  model.on("change:spots", draw);
  for (const name of ["width", "height", "scale", "cursor"]) model.on(`change:${name}`, resize);
  resize();
  queueImage();

  return () => {
    model.off("change:image", queueImage);
    model.off("change:markers", draw);
    model.off("change:spots", draw);
    for (const name of ["width", "height", "scale", "cursor"]) model.off(`change:${name}`, resize);
  };
}

export default { render };
