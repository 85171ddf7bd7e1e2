/* The cosim coupling client, C interface (libcosim_client, docs/clients.md).
 *
 * One handle per solver process. Configure it (cosim_parse_args, or the cosim_set_* calls), then
 * cosim_hello() connects to the coupler, handshakes and starts the heartbeats; loop on cosim_next() as in
 * docs/protocol.md "Writing a solver client"; cosim_close() ends it.
 *
 * Every function that can fail returns COSIM_OK (0) or one of the COSIM_E_* codes; cosim_last_error() then
 * gives the message (per thread). Arrays are flat: `dim` values per face for vectors, face-major
 * `face * phases + phase` for per-phase data. SI units. Nothing here is ZeroMQ or protobuf. */
#ifndef COSIM_CLIENT_H
#define COSIM_CLIENT_H

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__)
#define COSIM_API __attribute__((visibility("default")))
#else
#define COSIM_API
#endif

/* Status codes. */
enum {
  COSIM_OK = 0,
  COSIM_E_ARGUMENT = 1,  /* a wrong argument or a call out of order */
  COSIM_E_SCENE = 2,     /* the scene file or an override cannot be read */
  COSIM_E_REFUSED = 3,   /* the coupler refused the handshake (token, version, scene hash, role) */
  COSIM_E_PEER_LOST = 4, /* the coupler stopped answering */
  COSIM_E_PROTOCOL = 5,  /* a malformed or unexpected message (the coupler has been told) */
  COSIM_E_STOPPED = 6,   /* the coupler stopped the run with a failure (the message is its reason) */
  COSIM_E_NOT_FOUND = 7, /* a scene key that is not there */
  COSIM_E_FAILED = 8,    /* anything else */
  COSIM_E_CORRUPT = 9    /* a checkpoint set or part that does not match its manifest (the message names the file) */
};

enum { COSIM_ROLE_FLUID = 1, COSIM_ROLE_SOLID = 2 };

/* What cosim_next() asks for. */
enum { COSIM_ADVANCE = 0, COSIM_OUTPUT = 1, COSIM_CHECKPOINT = 2, COSIM_STOP = 3 };

/* Interface conditions (cosim_mode) and cycle order (cosim_scheme), docs/protocol.md. */
enum { COSIM_MODE_IMPEDANCE = 0, COSIM_MODE_STANDARD = 1, COSIM_MODE_CHARACTERISTIC = 2, COSIM_MODE_ROBIN = 3 };
enum { COSIM_SCHEME_PIPELINED = 0, COSIM_SCHEME_SEQUENTIAL = 1 };

/* Fields of received faces (cosim_faces_get). */
enum {
  COSIM_FACE_CENTRE = 0,         /* dim per face [m] */
  COSIM_FACE_NORMAL = 1,         /* dim per face, out of the solid */
  COSIM_FACE_AREA = 2,           /* [m^2] */
  COSIM_FACE_VELOCITY = 3,       /* dim per face [m/s] */
  COSIM_FACE_NORMAL_STRESS = 4,  /* [Pa], tension positive */
  COSIM_FACE_IMPEDANCE = 5,      /* [Pa s/m], +inf for rigid */
  COSIM_FACE_VERTEX_POSITION = 6 /* dim per vertex [m] */
};

/* Fields of received interface states (cosim_states_get). */
enum {
  COSIM_STATE_PRESSURE = 0,             /* fluid: count * phases [Pa] */
  COSIM_STATE_NORMAL_VELOCITY = 1,      /* fluid: count * phases [m/s] */
  COSIM_STATE_FACE_PRESSURE = 2,        /* solid: count [Pa] */
  COSIM_STATE_FACE_NORMAL_VELOCITY = 3, /* solid: count [m/s] */
  COSIM_STATE_FACE_WETTED = 4,          /* solid: count, 1.0 or 0.0 */
  COSIM_STATE_FACE_IMPEDANCE = 5        /* solid, mode robin: count [Pa s/m] (0 values in other modes) */
};

typedef struct cosim_client cosim_client; /* opaque */

/* One directive of the coupler. Strings: cosim_stop_reason(), cosim_checkpoint_directory(). */
typedef struct cosim_directive {
  int kind;         /* COSIM_ADVANCE, COSIM_OUTPUT, COSIM_CHECKPOINT or COSIM_STOP */
  int output_index; /* COSIM_OUTPUT: the snapshot index */
  long long cycle;
  double time; /* t^n [s] (COSIM_OUTPUT: the snapshot time) */
  double dt;   /* COSIM_ADVANCE: the step [s]; 0 in cycle 0 (exchange only) */
} cosim_directive;

/* The message of this thread's last failed call ("" when none). */
COSIM_API const char* cosim_last_error(void);
COSIM_API const char* cosim_library_version(void); /* e.g. "0.9.0" */
COSIM_API int cosim_protocol_version(void);

/* The scene hash of a file and its overrides ("key.path=value"), 16 hex digits and a NUL into out. */
COSIM_API int cosim_scene_hash(const char* scene_file, const char* const* overrides, int n_overrides, char out[17]);

/* A handle for a COSIM_ROLE_FLUID or COSIM_ROLE_SOLID solver; nothing is connected yet. */
COSIM_API int cosim_create(cosim_client** out, int role);

/* The usual solver command line, argv[0] skipped: SCENE --out DIR --coupler ENDPOINT [--token T]
 * [--set key=value]... [--restart SET]. Any other argument is an error (COSIM_E_ARGUMENT). */
COSIM_API int cosim_parse_args(cosim_client* c, int argc, char** argv);

/* The same settings one by one. Without a token, cosim_hello() takes $COSIM_TOKEN; without a scene hash, the
 * hash of the scene file and overrides. */
COSIM_API int cosim_set_endpoint(cosim_client* c, const char* endpoint);
COSIM_API int cosim_set_token(cosim_client* c, const char* token);
COSIM_API int cosim_set_scene(cosim_client* c, const char* scene_file);
COSIM_API int cosim_add_override(cosim_client* c, const char* assignment);
COSIM_API int cosim_set_scene_hash(cosim_client* c, const char* hash);
COSIM_API int cosim_set_program(cosim_client* c, const char* name);                    /* for the coupler's messages */
COSIM_API int cosim_add_phase(cosim_client* c, const char* name, double min_pressure); /* fluid, in sample order */
COSIM_API int cosim_set_restart(cosim_client* c, long long cycle, double time);        /* restored from a set */
COSIM_API int cosim_set_connect_timeout(cosim_client* c, double seconds);              /* default 30 s */
/* A solver on several MPI ranks connects from one of them and says for how many it speaks (1 to 1000000;
 * default 1). */
COSIM_API int cosim_set_ranks(cosim_client* c, int ranks);

/* What the command line said ("" when not given; out: "." by default). Valid while the handle lives. */
COSIM_API const char* cosim_scene_file(const cosim_client* c);
COSIM_API const char* cosim_out_dir(const cosim_client* c);
COSIM_API const char* cosim_restart_set(const cosim_client* c);

/* Reading the scene (file + overrides, as the solvers read it). Keys are dotted paths, list entries by index:
 * "solid.blocks.0.density". A missing key is COSIM_E_NOT_FOUND. Strings stay valid until the next call. */
COSIM_API int cosim_scene_has(cosim_client* c, const char* key, int* present);
COSIM_API int cosim_scene_length(cosim_client* c, const char* key, int* length); /* entries of a list or map */
COSIM_API int cosim_scene_number(cosim_client* c, const char* key, double* value);
COSIM_API int cosim_scene_numbers(cosim_client* c, const char* key, double* out, int capacity, int* length);
COSIM_API int cosim_scene_string(cosim_client* c, const char* key, const char** value);

/* Connects, handshakes (token, protocol version, scene hash) and starts the heartbeats. */
COSIM_API int cosim_hello(cosim_client* c);

/* Waits for the next directive. A Stop without failure is COSIM_OK with kind COSIM_STOP. */
COSIM_API int cosim_next(cosim_client* c, cosim_directive* d);
COSIM_API const char* cosim_stop_reason(const cosim_client* c);          /* of the last COSIM_STOP */
COSIM_API const char* cosim_checkpoint_directory(const cosim_client* c); /* of the last COSIM_CHECKPOINT */

/* Solid, once per cycle: its faces. velocity, normal_stress and impedance may be NULL (0, 0, +inf: rigid);
 * vertex_position and face_vertex may be NULL with nodes_per_face = 0. */
COSIM_API int cosim_send_faces(cosim_client* c, int dim, int count, const double* centre, const double* normal,
                               const double* area, const double* velocity, const double* normal_stress,
                               const double* impedance, int nodes_per_face, int vertex_count,
                               const double* vertex_position, const int* face_vertex);

/* Fluid, once per cycle: the solid's faces, held until the next call; then copy the fields out. Copies fail
 * with COSIM_E_ARGUMENT when capacity < *length (length is set either way). */
COSIM_API int cosim_receive_faces(cosim_client* c, int* dim, int* count, int* nodes_per_face, int* vertex_count);
COSIM_API int cosim_faces_get(const cosim_client* c, int field, double* out, int capacity, int* length);
COSIM_API int cosim_faces_vertices(const cosim_client* c, int* out, int capacity, int* length);

/* Fluid, once per cycle: the samples next to each face (count * phases each; impedance may be NULL; wetted: count
 * values, 0 or 1). */
COSIM_API int cosim_send_samples(cosim_client* c, int count, int phases, const double* alpha, const double* rho,
                                 const double* normal_velocity, const double* pressure, const double* impedance,
                                 const int* wetted);

/* Both, once per cycle: the interface states, held until the next call; then copy the fields out. */
COSIM_API int cosim_receive_states(cosim_client* c, int* count, int* phases);
COSIM_API int cosim_states_get(const cosim_client* c, int field, double* out, int capacity, int* length);

COSIM_API int cosim_propose_dt(cosim_client* c, double dt); /* both, once per cycle [s] */
/* Answers COSIM_CHECKPOINT: this solver's part (a file name in the set directory) is written. */
COSIM_API int cosim_confirm_checkpoint(cosim_client* c, const char* part, long long bytes);

/* Checkpoints (docs/checkpoint_restart.md; format cosim-checkpoint-set-2). A part is any bytes of the solver's
 * choosing, one file in the set directory. */
/* Answers COSIM_CHECKPOINT in one call: writes `bytes` of `data` as the file `part` in cosim_checkpoint_directory()
 * (under a temporary name, fsynced and renamed: whole or absent), PART.sha256 beside it (sha256sum's format, from
 * the bytes written; the coupler's manifest records it), and confirms the part to the coupler. */
COSIM_API int cosim_write_part(cosim_client* c, const char* part, const void* data, long long bytes);
/* Checks the part `part` of the checkpoint set directory `set` (the --restart argument) against the set's
 * manifest.json: its format, its cycle against the directory's name, the part listed with a checksum, the file's
 * size and SHA-256. COSIM_E_CORRUPT names the file and what differs. Out (each may be NULL): the part's size, its
 * SHA-256 (64 hex digits and a NUL), the set's cycle and time (for cosim_set_restart). Needs no handle. */
COSIM_API int cosim_client_verify_part(const char* set, const char* part, long long* bytes, char sha256[65],
                                       long long* cycle, double* time);
/* Reads the part into out[0..capacity) after the same checks, made on the bytes read (no second read that could
 * differ); *length is the part's size (set also when capacity is too small: COSIM_E_ARGUMENT). */
COSIM_API int cosim_read_part(const char* set, const char* part, void* out, long long capacity, long long* length);
/* Of the work since the last message, `seconds` went into writing outputs (kept apart in the coupler's timing). */
COSIM_API int cosim_add_output_seconds(cosim_client* c, double seconds);
/* Tells the coupler this solver cannot go on (best effort; call it before exiting non-zero). */
COSIM_API void cosim_report_error(cosim_client* c, const char* reason);
/* COSIM_E_PEER_LOST when the coupler's heartbeats stopped (for long steps between calls). */
COSIM_API int cosim_check(const cosim_client* c);

/* After cosim_hello(). */
COSIM_API int cosim_mode(const cosim_client* c);   /* COSIM_MODE_* */
COSIM_API int cosim_scheme(const cosim_client* c); /* COSIM_SCHEME_* */
COSIM_API long long cosim_cycle(const cosim_client* c);
COSIM_API double cosim_time(const cosim_client* c);    /* t^n of the current cycle [s] */
COSIM_API double cosim_timeout(const cosim_client* c); /* [s] */

/* Stops the heartbeats, closes the connections and frees the handle (NULL is fine). */
COSIM_API void cosim_close(cosim_client* c);

#ifdef __cplusplus
}
#endif

#endif /* COSIM_CLIENT_H */
