// refracta.widgets readout viewer (anywidget ES module): the rendered PNG, and under the pointer
// the per-pixel readouts of render(aovs=[...]) read from one float32 buffer in the browser (no
// round trip to the kernel: hovering works wherever the widget shows).
//
// Model traits: image (PNG bytes), width/height (image pixels), scale (display pixels per image
// pixel), values (float32 little-endian bytes, height x width x channels, row-major),
// layout ([{name, offset, labels: [..], unit, units: [..], digits: [..]}]: each readout's first
// channel, its channels' labels, the unit after all values or each value's own, and each value's
// decimals), text (the readout shown; also set on hover, so Python sees the last one).

function formatValue(value, digits, unit) {
  if (Number.isNaN(value)) return "none";
  if (!Number.isFinite(value)) return value > 0 ? "inf" : "-inf";
  return value.toFixed(digits) + (unit ? ` ${unit}` : "");
}

function render({ model, el }) {
  const box = document.createElement("div");
  const img = document.createElement("img");
  const label = document.createElement("pre");
  img.className = "refracta-readouts";
  img.style.imageRendering = "pixelated";
  label.style.margin = "4px 0";
  label.style.fontSize = "12px";
  box.appendChild(img);
  box.appendChild(label);
  el.appendChild(box);
  let url = null;

  function show() {
    if (url) URL.revokeObjectURL(url);
    const bytes = model.get("image");
    url = URL.createObjectURL(new Blob([bytes], { type: "image/png" }));
    img.src = url;
    img.style.width = `${Math.round(model.get("width") * model.get("scale"))}px`;
    label.textContent = model.get("text");
  }

  function readout(u, v) {
    const width = model.get("width"), height = model.get("height");
    const i = Math.min(width - 1, Math.max(0, Math.floor(u))), j = Math.min(height - 1, Math.max(0, Math.floor(v)));
    const buffer = model.get("values");
    const view = new DataView(buffer.buffer || buffer, buffer.byteOffset || 0);
    const layout = model.get("layout");
    const channels = layout.reduce((n, item) => n + item.labels.length, 0);
    const lines = [`pixel (${i}, ${j})`];
    for (const item of layout) {
      let met = false;  // "none", not "none deg"
      const parts = item.labels.map((labelText, c) => {
        const value = view.getFloat32(4 * ((j * width + i) * channels + item.offset + c), true);
        met = met || !Number.isNaN(value);
        return (labelText ? `${labelText} ` : "") + formatValue(value, item.digits[c], item.units[c]);
      });
      lines.push(`${item.name}: ${parts.join(", ")}${item.unit && met ? " " + item.unit : ""}`);
    }
    return lines.join("\n");
  }

  img.addEventListener("pointermove", (event) => {
    const rect = img.getBoundingClientRect();
    const u = (event.clientX - rect.left) / rect.width * model.get("width");
    const v = (event.clientY - rect.top) / rect.height * model.get("height");
    const text = readout(u, v);
    label.textContent = text;
    model.set("text", text);
    model.save_changes();
  });
  model.on("change:image", show);
  model.on("change:scale", show);
  show();
  return () => { if (url) URL.revokeObjectURL(url); };
}

export default { render };
