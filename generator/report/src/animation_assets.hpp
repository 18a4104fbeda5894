#pragma once
// The files the animation page carries, embedded into the program at build time
// (cmake/EmbedFiles.cmake, from generator/CMakeLists.txt): nothing is looked up at run time.
#include <string>

namespace eomgen::animation_assets {

std::string three_js();              // three.min.js of libjs-three
std::string orbit_controls_js();     // its examples/js/controls/OrbitControls.js
std::string three_js_copyright();    // /usr/share/doc/libjs-three/copyright

std::string page_html();   // generator/report/animation/page.html, the template
std::string viewer_css();  // generator/report/animation/viewer.css
std::string viewer_js();   // generator/report/animation/viewer.js

}  // namespace eomgen::animation_assets
