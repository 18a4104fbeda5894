#pragma once
// The animated 3D view of a simulation: one self-contained HTML page (three.js, the viewer and
// the data inline; no request of any kind when it is viewed). docs/animation.md describes the
// page and the scene data it reads, the contract between the simulation and the viewer.
#include <string>

namespace eomgen {

/// The whole HTML page showing `scene_json` (a scene of docs/animation.md, `"format": 1`),
/// titled `title`. The title is HTML-escaped; the scene goes into a
/// `<script type="application/json">` element with every `<` written `\u003c`, so no text in
/// it (model names come from user files) can end that element. The same arguments give the
/// same bytes. The JSON is not parsed here: the page reports a scene it cannot read.
std::string animation_page(const std::string& title, const std::string& scene_json);

/// The version of three.js the page embeds (libjs-three's, "r111").
std::string embedded_three_js_revision();

}  // namespace eomgen
