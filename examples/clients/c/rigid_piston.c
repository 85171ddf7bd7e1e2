/* A rigid piston as the solid of a coupled run, in C over libcosim_client: the physics of
 * python/cosim/rigid_piston.py (docs/clients.md).
 *
 *   rigid_piston SCENE --out DIR --coupler ENDPOINT [--token T] [--set key=value]... [--restart SET]
 *
 * The closed boundary of a rigid slab [left, right] x (the solid mesh's transverse box) moving along x: 2 points
 * (1D), 4 segments (2D) or 6 quads (3D) with their vertices. Newton's law under the interface pressures of the
 * previous cycle, symplectic Euler; under coupling.mode robin the face pressure follows the fluid's impedance Z
 * at the new velocity, taken implicitly: (m + theta dt K) v' = m v + dt (F + b - (1 - theta) K v),
 * K = sum Z A n_x^2, b = K v_sent, theta = max(1/2, 1 - m / (dt K)). Mass and geometry from the scene's solid:
 * box mesh with a rigid block named "piston". Writes DIR/piston.csv (t, x, v, F) at every output; at a checkpoint
 * its state as the part solid.bin of the set (cosim_write_part), which --restart SET resumes from after the
 * library checked it against the set's manifest (cosim_client_verify_part, cosim_read_part). */
#define _XOPEN_SOURCE 700 /* truncate() */
#include <cosim/client.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define MAX_FACES 6
#define PART "solid.bin"
/* The part: doubles, all exact. [0] layout version, [1] cycle, [2] time, [3] x, [4] v, [5] force, [6] v_sent,
 * [7] bytes of piston.csv written, [8] face count n, then n face pressures and n impedances. */
#define STATE_VERSION 1.0
#define STATE_HEAD 9
#define STATE_MAX (STATE_HEAD + 2 * MAX_FACES)

typedef struct {
  double mass, area, left, right;
  int dim;
  double lower[2], upper[2]; /* transverse extent (y, z) */
} Piston;

typedef struct {
  int count, nodes_per_face, vertex_count;
  double centre[MAX_FACES * 3], normal[MAX_FACES * 3], area[MAX_FACES], velocity[MAX_FACES * 3];
  double vertex[8 * 3];
  int face_vertex[MAX_FACES * 4];
} Faces;

/* Mass, cross-section and extent from the scene's solid: section (solid_solver box mesh, rigid block "piston");
 * 0 when the scene does not describe one (then the defaults of rigid_piston.py). */
static int piston_from_scene(cosim_client* c, Piston* p) {
  double lo[3], hi[3], density = 0;
  int n = 0, m = 0, blocks = 0, regions = 0, found = 0;
  char key[128];
  if (cosim_scene_numbers(c, "solid.mesh.lower", lo, 3, &n) || cosim_scene_numbers(c, "solid.mesh.upper", hi, 3, &m) ||
      n != m || n < 1 || cosim_scene_length(c, "solid.blocks", &blocks))
    return 0;
  for (int b = 0; b < blocks && !found; ++b) {
    const char* name = NULL;
    snprintf(key, sizeof key, "solid.blocks.%d.name", b);
    if (cosim_scene_string(c, key, &name) == COSIM_OK && strcmp(name, "piston") == 0) {
      snprintf(key, sizeof key, "solid.blocks.%d.density", b);
      found = cosim_scene_number(c, key, &density) == COSIM_OK;
    }
  }
  if (!found) return 0;
  p->left = lo[0];
  p->right = hi[0];
  if (cosim_scene_length(c, "solid.mesh.regions", &regions)) regions = 0;
  for (int r = 0; r < regions; ++r) {
    const char* block = NULL;
    double rlo[3], rhi[3];
    int k = 0;
    snprintf(key, sizeof key, "solid.mesh.regions.%d.block", r);
    if (cosim_scene_string(c, key, &block) || strcmp(block, "piston") != 0) continue;
    snprintf(key, sizeof key, "solid.mesh.regions.%d.lower", r);
    if (cosim_scene_numbers(c, key, rlo, 3, &k)) return 0;
    snprintf(key, sizeof key, "solid.mesh.regions.%d.upper", r);
    if (cosim_scene_numbers(c, key, rhi, 3, &k)) return 0;
    p->left = fmax(lo[0], rlo[0]);
    p->right = fmin(hi[0], rhi[0]);
  }
  p->dim = n;
  p->area = 1.0;
  for (int d = 1; d < n; ++d) {
    p->area *= hi[d] - lo[d];
    p->lower[d - 1] = lo[d];
    p->upper[d - 1] = hi[d];
  }
  p->mass = density * (p->right - p->left) * p->area;
  return 1;
}

/* The slab's boundary: outward normals, vertices, the rigid velocity (v, 0, 0); rigid and unstressed (the
 * library's defaults for impedance and normal stress). */
static void box_faces(const Piston* p, double x0, double x1, double v, Faces* f) {
  static const int faces2[4][2] = {{3, 0}, {1, 2}, {0, 1}, {2, 3}}; /* -x, +x, -y, +y */
  static const int faces3[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  const int dim = p->dim;
  double xs[2] = {x0, x1};
  f->count = 2 * dim;
  f->nodes_per_face = dim == 3 ? 4 : dim;
  f->vertex_count = 1 << dim;
  for (int i = 0; i < f->vertex_count; ++i) { /* 2D: counter-clockwise from (x0, y0); 3D: index = x + 2y + 4z */
    const int ix = dim == 2 ? (i == 1 || i == 2) : i & 1;
    f->vertex[i * dim] = xs[ix];
    for (int d = 1; d < dim; ++d) f->vertex[i * dim + d] = (i >> d) & 1 ? p->upper[d - 1] : p->lower[d - 1];
  }
  for (int k = 0; k < f->count; ++k) {
    for (int j = 0; j < f->nodes_per_face; ++j)
      f->face_vertex[k * f->nodes_per_face + j] = dim == 1 ? k : dim == 2 ? faces2[k][j] : faces3[k][j];
    for (int d = 0; d < dim; ++d) f->normal[k * dim + d] = d == k / 2 ? (k % 2 ? 1.0 : -1.0) : 0.0;
    double size = 1.0;
    for (int d = 0; d < dim; ++d) {
      double sum = 0, lo = INFINITY, hi = -INFINITY;
      for (int j = 0; j < f->nodes_per_face; ++j) {
        const double x = f->vertex[f->face_vertex[k * f->nodes_per_face + j] * dim + d];
        sum += x;
        lo = fmin(lo, x);
        hi = fmax(hi, x);
      }
      f->centre[k * dim + d] = sum / f->nodes_per_face;
      if (f->normal[k * dim + d] == 0) size *= hi - lo;
      f->velocity[k * dim + d] = d == 0 ? v : 0.0;
    }
    f->area[k] = dim > 1 ? size : p->area;
  }
}

/* The state of the set `set` (after the library's checks against its manifest) into the variables of main(). */
static int restore(const char* set, int nf, double* state, long long* cycle) {
  long long bytes = 0;
  double time = 0;
  if (cosim_client_verify_part(set, PART, NULL, NULL, cycle, &time) ||
      cosim_read_part(set, PART, state, (long long)(STATE_MAX * sizeof(double)), &bytes)) {
    fprintf(stderr, "[rigid_piston.c] error: --restart %s: %s\n", set, cosim_last_error());
    return 0;
  }
  if (bytes != (long long)((STATE_HEAD + 2 * nf) * sizeof(double)) || state[0] != STATE_VERSION || state[8] != nf ||
      state[1] != (double)*cycle) {
    fprintf(stderr,
            "[rigid_piston.c] error: --restart %s: %s/" PART
            " is not this piston's state of cycle %lld (%lld bytes, "
            "layout %g, %g faces, cycle %g)\n",
            set, set, *cycle, bytes, state[0], state[8], state[1]);
    return 0;
  }
  return 1;
}

static int failed(cosim_client* c, const char* what) {
  fprintf(stderr, "[rigid_piston.c] error: %s: %s\n", what, cosim_last_error());
  cosim_report_error(c, cosim_last_error());
  cosim_close(c);
  return 5;
}

int main(int argc, char** argv) {
  cosim_client* c = NULL;
  if (cosim_create(&c, COSIM_ROLE_SOLID) || cosim_parse_args(c, argc, argv)) {
    fprintf(stderr, "[rigid_piston.c] error: %s\n", cosim_last_error());
    cosim_close(c);
    return 2;
  }
  cosim_set_program(c, "rigid_piston.c");
  Piston p = {1.0, 1.0, -0.5, 0.5, 2, {0.0, 0.0}, {1.0, 1.0}};
  piston_from_scene(c, &p);
  Faces f;
  box_faces(&p, p.left, p.right, 0.0, &f);
  double area[MAX_FACES], nx[MAX_FACES];
  const int nf = f.count;
  for (int k = 0; k < nf; ++k) {
    area[k] = f.area[k];
    nx[k] = f.normal[k * p.dim];
  }
  double x = 0, v = 0, force = 0, v_sent = 0, pressure[MAX_FACES] = {0}, z[MAX_FACES] = {0};

  char path[4096];
  snprintf(path, sizeof path, "%s/piston.csv", cosim_out_dir(c));
  const char* set = cosim_restart_set(c);
  long long csv_bytes = 0;
  if (set[0]) { /* the state of the set's cycle; piston.csv cut back to where it was then */
    double state[STATE_MAX];
    long long cycle = 0;
    if (!restore(set, nf, state, &cycle) || cosim_set_restart(c, cycle, state[2])) {
      cosim_close(c);
      return 2;
    }
    x = state[3], v = state[4], force = state[5], v_sent = state[6], csv_bytes = (long long)state[7];
    for (int i = 0; i < nf; ++i) pressure[i] = state[STATE_HEAD + i], z[i] = state[STATE_HEAD + nf + i];
  }
  FILE* out = NULL;
  if (mkdir(cosim_out_dir(c), 0777) == 0 || errno == EEXIST)
    out = set[0] ? (truncate(path, (off_t)csv_bytes) == 0 ? fopen(path, "a") : NULL) : fopen(path, "w");
  if (!out) {
    fprintf(stderr, "[rigid_piston.c] error: cannot write %s: %s\n", path, strerror(errno));
    cosim_close(c);
    return 4;
  }
  if (!set[0]) fprintf(out, "time,x,v,force\n");
  if (cosim_hello(c)) return failed(c, "connect");
  for (;;) {
    cosim_directive d;
    if (cosim_next(c, &d)) return failed(c, "next");
    if (d.kind == COSIM_STOP) {
      fprintf(stderr, "[rigid_piston.c] stop: %s\n", cosim_stop_reason(c));
      break;
    }
    if (d.kind == COSIM_OUTPUT) {
      fprintf(out, "%.12g,%.12g,%.12g,%.12g\n", d.time, x, v, force);
      fflush(out);
      continue;
    }
    if (d.kind == COSIM_CHECKPOINT) { /* the state as doubles (exact), written and confirmed by the library */
      double state[STATE_MAX] = {STATE_VERSION, (double)cosim_cycle(c), cosim_time(c), x, v, force, v_sent, 0, nf};
      fflush(out);
      state[7] = (double)ftell(out);
      for (int i = 0; i < nf; ++i) state[STATE_HEAD + i] = pressure[i], state[STATE_HEAD + nf + i] = z[i];
      if (cosim_write_part(c, PART, state, (long long)((STATE_HEAD + 2 * nf) * sizeof(double))))
        return failed(c, "checkpoint");
      continue;
    }
    const double dt = d.dt;
    double k = 0;
    force = 0;
    for (int i = 0; i < nf; ++i) {
      force += -pressure[i] * area[i] * nx[i];
      k += z[i] * area[i] * (nx[i] * nx[i]);
    }
    if (k > 0 && dt > 0) {
      const double theta = fmax(0.5, 1.0 - p.mass / (dt * k));
      const double v_new = (p.mass * v + dt * (force + k * v_sent - (1.0 - theta) * k * v)) / (p.mass + theta * dt * k);
      force += k * (v_sent - ((1.0 - theta) * v + theta * v_new)); /* the Robin part, for piston.csv */
      v = v_new;
    } else {
      v += dt * force / p.mass;
    }
    x += dt * v;
    box_faces(&p, p.left + x, p.right + x, v, &f);
    int count = 0, phases = 0, n = 0;
    if (cosim_send_faces(c, p.dim, f.count, f.centre, f.normal, f.area, f.velocity, NULL, NULL, f.nodes_per_face,
                         f.vertex_count, f.vertex, f.face_vertex) ||
        cosim_propose_dt(c, 1.0) || cosim_receive_states(c, &count, &phases) ||
        cosim_states_get(c, COSIM_STATE_FACE_PRESSURE, pressure, MAX_FACES, &n) ||
        cosim_states_get(c, COSIM_STATE_FACE_IMPEDANCE, z, MAX_FACES, &n))
      return failed(c, "cycle");
    v_sent = v;
  }
  fclose(out);
  cosim_close(c);
  return 0;
}
