// A self-contained HTML page that plays a folding texture with WebGL 2: the same evaluation (fold.glsl via
// webShaderSource), the textures embedded as base64 of their raw 8/16-bit texels.
#include <sylva/folding/gpu/ShaderExport.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>

namespace sylva::folding::gpu {

namespace {

std::string base64(const std::byte* data, std::size_t size) {
  static constexpr std::array<char, 64> kAlphabet = {
      'A', 'B', 'C', 'D', 'E', 'F', 'G', 'H', 'I', 'J', 'K', 'L', 'M', 'N', 'O', 'P',
      'Q', 'R', 'S', 'T', 'U', 'V', 'W', 'X', 'Y', 'Z', 'a', 'b', 'c', 'd', 'e', 'f',
      'g', 'h', 'i', 'j', 'k', 'l', 'm', 'n', 'o', 'p', 'q', 'r', 's', 't', 'u', 'v',
      'w', 'x', 'y', 'z', '0', '1', '2', '3', '4', '5', '6', '7', '8', '9', '+', '/'};
  const auto* p = reinterpret_cast<const std::uint8_t*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (std::size_t i = 0; i < size; i += 3) {
    const std::uint32_t b0 = p[i];
    const std::uint32_t b1 = i + 1 < size ? p[i + 1] : 0;
    const std::uint32_t b2 = i + 2 < size ? p[i + 2] : 0;
    const std::uint32_t v = (b0 << 16) | (b1 << 8) | b2;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < size ? kAlphabet[(v >> 6) & 63] : '=';
    out += i + 2 < size ? kAlphabet[v & 63] : '=';
  }
  return out;
}

std::string imageBase64(const Image& image) {
  return base64(image.data(), image.byteSize());
}

// The page: WebGL 2 with one full-screen triangle; texel (x, y) of the shown image is drawn at canvas pixel
// (x, H − 1 − y) so the page shows the image upright. Phases are computed in JS doubles, as the host of the
// exported snippet does.
constexpr const char* kPage = R"HTML(<!doctype html>
<html><head><meta charset="utf-8"><title>Sylva folding preview</title>
<style>
body { margin: 0; background: #202124; color: #ddd; font: 13px sans-serif; }
#c { display: block; margin: 12px auto; image-rendering: pixelated; }
#ui { text-align: center; } #ui input[type=range] { width: 320px; vertical-align: middle; }
#out { display: none; }
</style></head>
<body>
<canvas id="c"></canvas>
<div id="ui"><button id="play">pause</button> t <input id="time" type="range" min="0" step="0.001">
<span id="tval"></span> s &nbsp; speed <input id="speed" type="number" value="1" step="0.25" min="0" style="width:4em"></div>
<pre id="out"></pre>
<script>
"use strict";
const META = @META@;
const DATA = @DATA@;
const SHADER = @SHADER@;
function bytes(b64) {
  const s = atob(b64);
  const u = new Uint8Array(s.length);
  for (let i = 0; i < s.length; ++i) u[i] = s.charCodeAt(i);
  return u;
}
const canvas = document.getElementById("c");
const out = document.getElementById("out");
canvas.width = META.view[2];
canvas.height = META.view[3];
const gl = canvas.getContext("webgl2", {antialias: false, premultipliedAlpha: false, preserveDrawingBuffer: true});
function fail(message) { out.style.display = "block"; out.textContent = "error: " + message; document.title = "error"; throw new Error(message); }
if (!gl) fail("WebGL 2 is not available");
gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
function texture(unit, data, integer) {
  const t = gl.createTexture();
  gl.activeTexture(gl.TEXTURE0 + unit);
  gl.bindTexture(gl.TEXTURE_2D, t);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
  const [w, h] = META.size;
  if (integer) {
    const b = bytes(data);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA16UI, w, h, 0, gl.RGBA_INTEGER, gl.UNSIGNED_SHORT, new Uint16Array(b.buffer));
  } else {
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, w, h, 0, gl.RGBA, gl.UNSIGNED_BYTE, bytes(data));
  }
}
function compile(type, source) {
  const s = gl.createShader(type);
  gl.shaderSource(s, source);
  gl.compileShader(s);
  if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) fail(gl.getShaderInfoLog(s));
  return s;
}
const vs = "#version 300 es\nvoid main() { vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)); gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0); }";
const fs = "#version 300 es\nprecision highp float;\nprecision highp int;\nprecision highp sampler2D;\nprecision highp usampler2D;\n" + SHADER +
  "\nuniform ivec4 view;\nout vec4 fragColor;\nvoid main() {\n  ivec2 p = ivec2(gl_FragCoord.xy);\n" +
  "  fragColor = foldingSample(ivec2(view.x + p.x, view.y + view.w - 1 - p.y));\n}\n";
const program = gl.createProgram();
gl.attachShader(program, compile(gl.VERTEX_SHADER, vs));
gl.attachShader(program, compile(gl.FRAGMENT_SHADER, fs));
gl.linkProgram(program);
if (!gl.getProgramParameter(program, gl.LINK_STATUS)) fail(gl.getProgramInfoLog(program));
gl.useProgram(program);
const names = Object.keys(DATA);
names.forEach((name, unit) => {
  texture(unit, DATA[name], name !== "folding_color");
  gl.uniform1i(gl.getUniformLocation(program, name), unit);
});
gl.uniform4iv(gl.getUniformLocation(program, "view"), META.view);
const phaseLocation = gl.getUniformLocation(program, "folding_phase");
gl.bindVertexArray(gl.createVertexArray());
function draw(t) {
  const phases = META.profiles.map(p => { const v = t / p.period + p.shift; return v - Math.floor(v); });
  gl.uniform1fv(phaseLocation, phases.length ? phases : [0]);
  gl.viewport(0, 0, canvas.width, canvas.height);
  gl.drawArrays(gl.TRIANGLES, 0, 3);
}
const params = new URLSearchParams(location.search);
if (params.has("dump")) {
  draw(parseFloat(params.get("t") || "0"));
  const [w, h] = [canvas.width, canvas.height];
  const px = new Uint8Array(w * h * 4);
  gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
  const rows = [];
  for (let y = h - 1; y >= 0; --y) {
    let row = "";
    for (let i = y * w * 4; i < (y + 1) * w * 4; ++i) row += px[i].toString(16).padStart(2, "0");
    rows.push(row);
  }
  out.textContent = w + " " + h + "\n" + rows.join("\n");
  document.title = "done";
} else {
  const slider = document.getElementById("time");
  const speed = document.getElementById("speed");
  const button = document.getElementById("play");
  const label = document.getElementById("tval");
  slider.max = META.duration;
  let playing = true, t = 0, last = performance.now();
  button.onclick = () => { playing = !playing; button.textContent = playing ? "pause" : "play"; };
  slider.oninput = () => { t = parseFloat(slider.value); playing = false; button.textContent = "play"; };
  function frame(now) {
    if (playing) { t = (t + (now - last) / 1000 * (parseFloat(speed.value) || 0)) % META.duration; slider.value = t; }
    last = now;
    label.textContent = t.toFixed(2);
    draw(t);
    requestAnimationFrame(frame);
  }
  requestAnimationFrame(frame);
}
</script></body></html>
)HTML";

void replaceOnce(std::string& text, const std::string& key, const std::string& value) {
  text.replace(text.find(key), key.size(), value);
}

} // namespace

void writeWebPreview(const std::filesystem::path& path, const shader::Library& library,
                     const Project& project, const Textures& textures) {
  Project web = project;
  web.outputs.encoding = Outputs::Encoding::Rgba16;
  const EncodedInfo info = encodedInfo(web, textures);
  std::string shader = webShaderSource(library, web, info);
  // Only comments hold non-ASCII text (φ, ×); browsers differ on non-ASCII shader sources, so drop it.
  std::string ascii;
  for (char c : shader) {
    if (static_cast<unsigned char>(c) < 0x80) {
      ascii += c;
    } else if ((static_cast<unsigned char>(c) & 0xC0) == 0xC0) {
      ascii += '?'; // one '?' per UTF-8 sequence
    }
  }
  shader = std::move(ascii);
  nlohmann::ordered_json data;
  data["folding_color"] = imageBase64(textures.atlas.color);
  data["folding_init"] = imageBase64(encode16(textures.init, TextureKind::Init, info.jumpMax));
  for (std::size_t l = 0; l < textures.jump.size(); ++l) {
    data["folding_jump" + std::to_string(l)] =
        imageBase64(encode16(textures.jump[l], TextureKind::Jump, info.jumpMax));
  }
  for (std::size_t l = 0; l < textures.fold.size(); ++l) {
    data["folding_fold" + std::to_string(l)] =
        imageBase64(encode16(textures.fold[l], TextureKind::Fold, info.jumpMax));
  }
  const AtlasEntry& canvas = textures.atlas.entries.at(static_cast<std::size_t>(project.canvasIndex()));
  const Rect view = canvas.atlasRect();
  nlohmann::json profiles = nlohmann::json::array();
  double duration = 0.0;
  for (const Profile& p : project.profiles) {
    profiles.push_back({{"period", p.periodS}, {"shift", p.shift}});
    duration = std::max(duration, p.periodS);
  }
  const nlohmann::json meta = {{"size", {textures.width(), textures.height()}},
                               {"view", {view.min.x, view.min.y, view.width(), view.height()}},
                               {"profiles", profiles},
                               {"duration", duration}};
  std::string page = kPage;
  replaceOnce(page, "@META@", meta.dump());
  replaceOnce(page, "@DATA@", data.dump());
  replaceOnce(page, "@SHADER@", nlohmann::json(shader).dump());
  writeTextFile(path, page);
}

} // namespace sylva::folding::gpu
