// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl generate curve|loops|hole|holes : test data. Polygons (the paper's
// curves, two loops bounding one surface, and hole boundaries grown on a
// triangle mesh) as "x y z [nx ny nz]" text; meshes with holes cut out (and
// the removed patches).
#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "commands.h"
#include "exit_codes.h"

namespace dot::client {

void AddGenerateHolesCommand(CLI::App* gen, Context* ctx);

namespace {

// Writes a generated polygon to `out` (- for stdout); a failure is
// reported and sets the exit code.
void WritePolygonOut(const PolygonData& polygon, const std::string& out,
                     Context* ctx) {
  const Status s = out == "-" ? WritePolygonText(std::cout, polygon)
                              : WritePolygonText(out, polygon);
  if (!s.ok()) {
    std::cerr << "dotctl: " << s.message << "\n";
    ctx->exit_code = kExitFailed;
  }
}

}  // namespace

void AddGenerateCommand(CLI::App& app, Context* ctx) {
  CLI::App* gen = app.add_subcommand(
      "generate",
      "Write test data: the paper's curves, loop pairs, mesh holes or curve "
      "networks.");
  gen->require_subcommand(1);

  struct CurveFlags {
    std::string name;
    int n = 200;
    std::string out;
  };
  auto c = std::make_shared<CurveFlags>();
  CLI::App* curve = gen->add_subcommand(
      "curve", "monkey, mobius, spiral, moment, twist or trefoil (knotted)");
  curve->add_option("name", c->name, "curve name")->required();
  curve->add_option("-n,--vertices", c->n, "number of vertices")
      ->check(CLI::Range(3, 100000000))
      ->capture_default_str();
  curve
      ->add_option("-o,--output", c->out,
                   "polygon file to write (- for stdout)")
      ->required();
  curve->callback([c, ctx] {
    const auto which = CurveFromName(c->name);
    if (!which) {
      std::cerr << "dotctl: unknown curve '" << c->name << "'\n";
      ctx->exit_code = kExitUsage;
      return;
    }
    WritePolygonOut(PolygonData{MakeCurve(*which, c->n), {}}, c->out, ctx);
  });

  struct LoopsFlags {
    std::string name, out;
    int n = 100;
    uint64_t seed = 1;
  };
  auto lp = std::make_shared<LoopsFlags>();
  CLI::App* loops = gen->add_subcommand(
      "loops",
      "tube or island: two loops bounding one surface, in one file (blank "
      "line between them)");
  loops->add_option("name", lp->name, "tube or island")
      ->required()
      ->check(CLI::IsMember({"tube", "island"}));
  loops->add_option("-n,--vertices", lp->n, "vertices per loop")
      ->check(CLI::Range(3, 10000000))
      ->capture_default_str();
  loops->add_option("--seed", lp->seed, "random seed")->capture_default_str();
  loops
      ->add_option("-o,--output", lp->out,
                   "polygon file to write (- for stdout)")
      ->required();
  loops->callback([lp, ctx] {
    WritePolygonOut(MakeLoopPair(*LoopPairFromName(lp->name), lp->n, lp->seed),
                    lp->out, ctx);
  });

  struct HoleFlags {
    std::string mesh, out;
    int triangles = 200;
    uint64_t seed = 1;
  };
  auto h = std::make_shared<HoleFlags>();
  CLI::App* hole = gen->add_subcommand(
      "hole",
      "Grow a disk-shaped hole on a mesh (.off/.obj) and write its boundary "
      "with the mesh's normals");
  hole->add_option("mesh", h->mesh, "triangle mesh")->required();
  hole->add_option("-t,--triangles", h->triangles, "triangles to remove")
      ->capture_default_str();
  hole->add_option("--seed", h->seed, "random seed")->capture_default_str();
  hole->add_option("-o,--output", h->out,
                   "polygon file to write (- for stdout)")
      ->required();
  AddGenerateHolesCommand(gen, ctx);
  hole->callback([h, ctx] {
    MeshData mesh;
    Hole result;
    Status s = ReadMeshFile(h->mesh, &mesh);
    if (!s.ok()) {
      std::cerr << "dotctl: " << s.message << "\n";
      ctx->exit_code = kExitUsage;  // unreadable input
      return;
    }
    s = GrowHole(mesh, h->triangles, h->seed, &result);
    if (s.ok()) {
      s = h->out == "-" ? WritePolygonText(std::cout, result.boundary)
                        : WritePolygonText(h->out, result.boundary);
    }
    if (!s.ok()) {
      std::cerr << "dotctl: " << s.message << "\n";
      ctx->exit_code = kExitFailed;
      return;
    }
    if (!ctx->quiet) {
      (h->out == "-" ? std::cerr : std::cout)
          << "hole of " << result.triangles << " triangles, boundary of "
          << result.boundary.vertices.size() << " vertices -> " << h->out
          << std::endl;
    }
  });
}

void AddGenerateHolesCommand(CLI::App* gen, Context* ctx) {
  struct HolesFlags {
    std::string mesh, out, removed;
    int count = 10, triangles = 200, island = 0;
    uint64_t seed = 1;
  };
  auto h = std::make_shared<HolesFlags>();
  CLI::App* holes = gen->add_subcommand(
      "holes",
      "Cut k separate holes, grown to a size, out of a closed mesh (test data "
      "for fill-holes); the removed patches are written too (ground truth)");
  holes->add_option("mesh", h->mesh, "closed triangle mesh")->required();
  holes->add_option("-k,--count", h->count, "holes to cut")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  holes->add_option("-t,--triangles", h->triangles, "triangles per hole")
      ->check(CLI::Range(1, 100000000))
      ->capture_default_str();
  holes
      ->add_option("--island", h->island,
                   "leave an island of this many triangles floating in "
                   "each hole (0: none); the hole is the ring around it")
      ->check(CLI::Range(0, 100000000))
      ->capture_default_str();
  holes->add_option("--seed", h->seed, "random seed")->capture_default_str();
  holes->add_option("-o,--output", h->out, "the mesh with holes")->required();
  holes->add_option("--removed", h->removed,
                    "where the removed patches go (default: OUTPUT's name "
                    "with .removed before the extension)");
  holes->callback([h, ctx] {
    MeshData mesh, holey, removed;
    Status s = ReadMeshFile(h->mesh, &mesh);
    if (!s.ok()) {
      std::cerr << "dotctl: " << s.message << "\n";
      ctx->exit_code = kExitUsage;
      return;
    }
    std::string removed_path = h->removed;
    if (removed_path.empty()) {
      const std::filesystem::path p(h->out);
      removed_path = (p.parent_path() /
                      (p.stem().string() + ".removed" + p.extension().string()))
                         .string();
    }
    s = CutIslandHoles(mesh, h->count, h->triangles, h->island, h->seed, &holey,
                       &removed);
    if (s.ok()) s = WriteMeshFile(h->out, holey);
    if (s.ok()) s = WriteMeshFile(removed_path, removed);
    if (!s.ok()) {
      std::cerr << "dotctl: " << s.message << "\n";
      ctx->exit_code = kExitFailed;
      return;
    }
    if (!ctx->quiet) {
      std::cout << h->count << " holes of " << h->triangles << " triangles"
                << (h->island > 0
                        ? " around islands of " + std::to_string(h->island)
                        : std::string())
                << " -> " << h->out << " (removed patches: " << removed_path
                << ")\n";
    }
  });
  struct NetworkFlags {
    std::string source, out;
    int segments = 4, patches = 100, keep_every = 1;
    uint64_t seed = 1;
  };
  auto nf = std::make_shared<NetworkFlags>();
  CLI::App* network = gen->add_subcommand(
      "network",
      "Write a curve network (OBJ polylines) for surface: 'cube' (its 12 "
      "edges), 'cylinder' (two rims and a seam), or the rims of disk-shaped "
      "patches cut from a closed MESH file (its surface is the reference)");
  network->add_option("source", nf->source, "cube, cylinder, or a mesh file")
      ->required();
  network
      ->add_option("-s,--segments", nf->segments,
                   "cube: pieces per edge; cylinder: points per rim")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  network->add_option("-p,--patches", nf->patches, "mesh: patches to cut")
      ->check(CLI::Range(2, 1000000))
      ->capture_default_str();
  network
      ->add_option("--keep-every", nf->keep_every,
                   "mesh: keep the junctions and every k-th rim vertex")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  network->add_option("--seed", nf->seed, "random seed")->capture_default_str();
  network->add_option("-o,--output", nf->out, "network .obj (- for stdout)")
      ->required();
  network->callback([nf, ctx] {
    CurveNetwork net;
    Status s = OkStatus();
    if (nf->source == "cube") {
      net = CubeNetwork(nf->segments);
    } else if (nf->source == "cylinder") {
      net = CylinderNetwork(std::max(3, nf->segments), /*seam=*/true);
    } else {
      MeshData mesh;
      s = ReadMeshFile(nf->source, &mesh);
      CutNetwork cut;
      if (s.ok()) {
        s = CutIntoPatches(mesh, nf->patches, nf->keep_every, nf->seed, &cut);
      }
      net = std::move(cut.network);
    }
    if (s.ok()) {
      if (nf->out == "-") {
        s = WriteNetworkObj(std::cout, net);
      } else {
        std::ofstream out(nf->out);
        s = out ? WriteNetworkObj(out, net)
                : InvalidArgument("cannot write '" + nf->out + "'");
      }
    }
    if (!s.ok()) {
      std::cerr << "dotctl: " << s.message << "\n";
      ctx->exit_code = kExitFailed;
      return;
    }
    if (!ctx->quiet && nf->out != "-") {
      std::cerr << net.polylines.size() << " polylines, " << net.vertices.size()
                << " vertices -> " << nf->out << "\n";
    }
  });
}

}  // namespace dot::client
