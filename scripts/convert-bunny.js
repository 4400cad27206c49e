// One-off conversion of the npm package "bunny" (the Stanford bunny, public
// domain packaging by Mikola Lysenko) to Data/bunny.ply. Kept so the PLY's
// origin is reproducible:  npm pack bunny && tar xzf bunny-*.tgz &&
//   node scripts/convert-bunny.js package/index.js Data/bunny.ply
const fs = require("fs");
const bunny = require(require("path").resolve(process.argv[2]));
const out = [];
out.push("ply", "format ascii 1.0",
  "comment Stanford bunny (Stanford 3D Scanning Repository), via npm package bunny@1.0.1",
  `element vertex ${bunny.positions.length}`, "property float x", "property float y",
  "property float z", `element face ${bunny.cells.length}`,
  "property list uchar int vertex_indices", "end_header");
for (const p of bunny.positions) out.push(p.map((v) => +v.toFixed(6)).join(" "));
for (const c of bunny.cells) out.push(`3 ${c.join(" ")}`);
fs.writeFileSync(process.argv[3], out.join("\n") + "\n");
