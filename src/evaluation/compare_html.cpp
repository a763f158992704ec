// index.html of a comparison (`tripath compare`, tripath.compare): the chart, the table and the
// images in one page that works from the file system (relative links, no network, no libraries).
// The page checks itself: once loaded it sets data-images="loaded" on <body> if every image
// decoded, and lists script errors in #console-errors, which is what the headless-browser test
// reads.
#include <fmt/format.h>

#include <algorithm>

#include "evaluation/class_map.h"
#include "evaluation/compare.h"
#include "evaluation/markup.h"

namespace tripath::evaluation {

namespace {

std::string escape(const std::string& s) { return escapeMarkup(s); }

// Registered first, in <head>, so that errors while the images load are caught too.
constexpr const char* kErrorCapture = R"(<script>
const pageErrors = [];
function reportError(message) {
  pageErrors.push(String(message));
  const box = document.getElementById('console-errors');
  if (box) box.textContent = pageErrors.join('\n');
  document.documentElement.dataset.errors = pageErrors.length;
}
window.addEventListener('error', e => {
  reportError(e.message || ('could not load ' + (e.target && e.target.getAttribute && e.target.getAttribute('src'))));
}, true);
const consoleError = console.error.bind(console);
console.error = (...args) => { reportError(args.join(' ')); consoleError(...args); };
</script>
)";

constexpr const char* kStyle = R"(<style>
body { font-family: "DejaVu Sans", Verdana, sans-serif; margin: 2em; color: #222; max-width: 1400px; }
table { border-collapse: collapse; margin: 1em 0; }
th, td { border: 1px solid #bbb; padding: 0.3em 0.7em; text-align: right; }
th:first-child, td:first-child { text-align: left; }
#viewer { display: grid; width: 512px; }
#viewer img { grid-area: 1 / 1; width: 512px; image-rendering: pixelated; visibility: hidden; }
#viewer img.shown { visibility: visible; }
#buttons button { font-size: 1em; margin: 0 0.3em 0.5em 0; padding: 0.3em 0.8em; }
#buttons button.active { font-weight: bold; background: #ffd44d; }
#console-errors:empty { display: none; }
#console-errors { color: #b00; }
</style>
)";

constexpr const char* kViewerScript = R"(<script>
const views = [...document.querySelectorAll('#viewer img')];
const buttons = [...document.querySelectorAll('#buttons button')];
let chosen = buttons.length > 1 ? buttons[1].dataset.view : 'reference';
function show(name) {
  for (const img of views) img.classList.toggle('shown', img.dataset.view === name);
  for (const b of buttons) b.classList.toggle('active', b.dataset.view === name);
  const button = buttons.find(b => b.dataset.view === name);
  document.getElementById('caption').textContent = button ? button.dataset.caption : '';
}
function choose(name) { chosen = name; show(name); }
for (const b of buttons) b.addEventListener('click', () => choose(b.dataset.view));
const viewer = document.getElementById('viewer');
viewer.addEventListener('mousedown', () => show('reference'));
viewer.addEventListener('mouseup', () => show(chosen));
viewer.addEventListener('mouseleave', () => show(chosen));
document.addEventListener('keydown', e => {
  if (e.key === ' ') { show('reference'); e.preventDefault(); }
  const i = parseInt(e.key, 10);
  if (i >= 1 && i <= buttons.length) choose(buttons[i - 1].dataset.view);
});
document.addEventListener('keyup', e => { if (e.key === ' ') show(chosen); });
choose(chosen);
window.addEventListener('load', () => {
  const images = [...document.images];
  const broken = images.filter(i => !(i.complete && i.naturalWidth > 0)).map(i => i.getAttribute('src'));
  document.body.dataset.imageCount = images.length;
  document.body.dataset.images = broken.length ? 'broken: ' + broken.join(' ') : 'loaded';
});
</script>
)";

std::string table(const Report& r) {
    const MethodSummary& best = r.summaries[bestMethod(r.summaries)];
    std::string s = fmt::format(
        "<table id=\"summary\"><tr><th>method</th><th>relMSE</th><th>MSE</th><th>MAE</th><th>spp</th>"
        "<th>time to reach {}'s relMSE</th><th>efficiency 1/(relMSE·s)</th>"
        "<th title=\"per-sample relative variance of an unbiased method\">relMSE·spp</th>"
        "<th title=\"share of the relMSE carried by the 0.1 % of pixels with the largest error\">worst 0.1 % of "
        "pixels</th><th title=\"{}\">HDR-FLIP</th><th title=\"closest-hit and shadow rays per second of render time\">"
        "Mrays/s</th></tr>\n",
        escape(best.method), escape(kFlipDefinition));
    for (const MethodSummary& x : r.summaries) {
        s += fmt::format("<tr><td>{}</td><td>{:.4g}</td><td>{:.4g}</td><td>{:.4g}</td><td>{:.0f}</td><td>{}</td><td>{:.4g}</td>"
                         "<td>{:.4g}</td><td>{}</td><td>{:.4g}</td><td>{:.4g}</td></tr>\n",
                         escape(x.method), x.error.relMse, x.error.mse, x.error.mae, x.spp, timeToBestText(x), x.efficiency,
                         x.relVariance, tailShareText(x.error.tailShare), x.flip, x.raysPerSecond / 1e6);
    }
    return s + "</table>\n";
}

std::string viewer(const Report& r) {
    std::string buttons = fmt::format("<button data-view=\"reference\" data-caption=\"reference: {}\">reference</button>",
                                      escape(r.reference.description));
    std::string images = "<img data-view=\"reference\" src=\"reference.png\" alt=\"reference\">\n";
    for (const MethodSummary& x : r.summaries) {
        const Run& run0 = *std::find_if(r.runs.begin(), r.runs.end(),
                                        [&](const Run& run) { return run.method == x.method && run.index == 0; });
        const std::string caption = fmt::format("{}: {} spp in {}, relMSE {:.4g} (run 0)", x.method, run0.final().spp,
                                                formatSeconds(run0.final().seconds), run0.final().error.relMse);
        buttons += fmt::format("<button data-view=\"{0}\" data-caption=\"{1}\">{0}</button>", escape(x.method),
                               escape(caption));
        images += fmt::format("<img data-view=\"{0}\" src=\"{0}.png\" alt=\"{0}\">\n", escape(x.method));
    }
    // Each method's error map (error_map.h) as one more view.
    for (const MethodSummary& x : r.summaries) {
        buttons += fmt::format("<button data-view=\"{0}-error\" data-caption=\"{0}: relative squared error per pixel "
                               "(run 0; scale below)\">{0} error</button>",
                               escape(x.method));
        images += fmt::format("<img data-view=\"{0}-error\" src=\"{0}-error.png\" alt=\"{0} error map\">\n", escape(x.method));
    }
    // What auto chose where (class_map.h), as one more view of each method that says it.
    for (const auto& [method, channels] : r.channels) {
        buttons += fmt::format("<button data-view=\"{0}-classes\" data-caption=\"{0} (run 0): {1}\">{0} classes</button>",
                               escape(method), escape(kClassMapLegend));
        images += fmt::format("<img data-view=\"{0}-classes\" src=\"{0}-classes.png\" alt=\"{0}'s classes per tile\">\n",
                              escape(method));
    }
    return "<div id=\"buttons\">" + buttons + "</div>\n<div id=\"viewer\">\n" + images +
           "</div>\n<p id=\"caption\"></p>\n<img id=\"error-scale\" src=\"error-scale.png\" alt=\"error map colour scale\">\n";
}

}  // namespace

void writeIndexHtml(const Report& r, const std::string& path) {
    const std::string scene = escape(r.options.render.scene);
    std::string s = fmt::format("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                                "<title>tripath compare: {}</title>\n{}{}</head>\n<body data-images=\"pending\">\n",
                                scene, kStyle, kErrorCapture);
    s += fmt::format("<h1>tripath compare: {}</h1>\n<p>{}.<br>Reference: {}.</p>\n", scene,
                     escape(settingsLine(r.options)), escape(r.reference.description));
    s += "<h2>Error against time</h2>\n<img id=\"chart\" src=\"error-vs-time.svg\" width=\"800\" height=\"500\" "
         "alt=\"relMSE against render time, log-log, one line per method\">\n";
    s += "<h2>Final error</h2>\n" + table(r);
    s += "<h2>Images at equal time</h2>\n<p>Choose a method (or press 1, 2, …); hold the mouse button on the image, "
         "or the space bar, to see the reference in its place.</p>\n" + viewer(r);
    s += "<h2>Side by side</h2>\n<p>The outlined region is magnified below each image.</p>\n"
         "<img id=\"side-by-side\" src=\"side-by-side.png\" alt=\"reference and each method side by side\">\n";
    s += "<p>Data: <a href=\"error.csv\">error.csv</a>, <a href=\"counters.csv\">counters.csv</a>, <a href=\"summary.md\">summary.md</a>, "
         "<a href=\"error-vs-time.png\">chart as PNG</a>.</p>\n<pre id=\"console-errors\"></pre>\n";
    s += kViewerScript;
    s += "</body>\n</html>\n";
    writeText(path, s);
}

}  // namespace tripath::evaluation
