// MuJoCo's time per mj_forward through its C API, on an MJCF model with
// contacts, constraints and actuation disabled (as tests/reference/mjcf/
// compares): the counterpart of `mass_matrix` + `forcing` + the solve, that
// is of `dalembert::accelerations`. scripts/bench/humanoid.sh and mjcf.sh build
// and run it; scripts/mjcf_timing.py is the same measurement through the
// Python bindings (whose loop overhead it has to subtract).
//
// Build: cc -O2 mj_forward.c -I$MUJOCO/include $MUJOCO/libmujoco.so* -lm
//   ($MUJOCO: the folder of MuJoCo's headers and shared library, e.g. the
//   `mujoco` Python wheel's package folder)
// Usage: mj_forward MODEL.xml [--reps R] [--target-ms T]
// Output: CSV model,nq,nv,algo,median_ns,min_ns,max_ns,calls_per_rep, the
//   method of the peers' harness: 1000 random states (each coordinate moved by
//   U(-0.5, 0.5) from qpos0, free joints' quaternions normalised; qvel and
//   qfrc_applied U(-1, 1)), the median of R repeats of a loop over them, each
//   repeat long enough for T milliseconds, thread CPU time.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <mujoco/mujoco.h>

enum { STATES = 1000 };

static double thread_cpu_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

// A deterministic uniform draw in [-1, 1) (xorshift64*).
static double uniform(unsigned long long* s) {
  *s ^= *s >> 12;
  *s ^= *s << 25;
  *s ^= *s >> 27;
  return (double)((*s * 2685821657736338717ULL) >> 11) / 4503599627370496.0 - 1.0;
}

static int by_value(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

int main(int argc, char** argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: mj_forward MODEL.xml [--reps R] [--target-ms T]\n");
    return 1;
  }
  int reps = 9;
  double target_ms = 20;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (!strcmp(argv[i], "--reps")) reps = atoi(argv[i + 1]);
    else if (!strcmp(argv[i], "--target-ms")) target_ms = atof(argv[i + 1]);
    else { fprintf(stderr, "unknown argument %s\n", argv[i]); return 1; }
  }
  char error[1000] = "";
  mjModel* m = mj_loadXML(argv[1], NULL, error, sizeof error);
  if (!m) { fprintf(stderr, "%s: %s\n", argv[1], error); return 1; }
  m->opt.disableflags |= mjDSBL_CONTACT | mjDSBL_CONSTRAINT | mjDSBL_ACTUATION;
  mjData* d = mj_makeData(m);
  const int nq = m->nq, nv = m->nv;
  double* qpos = malloc(sizeof(double) * STATES * nq);
  double* qvel = malloc(sizeof(double) * STATES * nv);
  double* qfrc = malloc(sizeof(double) * STATES * nv);
  unsigned long long seed = 20261128;
  for (int k = 0; k < STATES; ++k) {
    double* q = qpos + k * nq;
    for (int i = 0; i < nq; ++i) q[i] = m->qpos0[i] + 0.5 * uniform(&seed);
    for (int j = 0; j < m->njnt; ++j) {
      if (m->jnt_type[j] != mjJNT_FREE) continue;
      double* quat = q + m->jnt_qposadr[j] + 3;
      double norm = sqrt(quat[0] * quat[0] + quat[1] * quat[1] + quat[2] * quat[2] + quat[3] * quat[3]);
      for (int i = 0; i < 4; ++i) quat[i] /= norm;
    }
    for (int i = 0; i < nv; ++i) {
      qvel[k * nv + i] = uniform(&seed);
      qfrc[k * nv + i] = uniform(&seed);
    }
  }
  // One pass over the states: the copies into mjData and one mj_forward each.
  double sink = 0.0;
#define PASS()                                                         \
  for (int k = 0; k < STATES; ++k) {                                   \
    memcpy(d->qpos, qpos + k * nq, sizeof(double) * nq);               \
    memcpy(d->qvel, qvel + k * nv, sizeof(double) * nv);               \
    memcpy(d->qfrc_applied, qfrc + k * nv, sizeof(double) * nv);       \
    mj_forward(m, d);                                                  \
    sink += d->qacc[0];                                                \
  }
  PASS();
  double t0 = thread_cpu_s();
  PASS();
  double once = thread_cpu_s() - t0;
  long passes = (long)ceil(target_ms * 1e-3 / (once > 1e-9 ? once : 1e-9));
  if (passes < 1) passes = 1;
  double* times = malloc(sizeof(double) * reps);
  for (int r = 0; r < reps; ++r) {
    double start = thread_cpu_s();
    for (long p = 0; p < passes; ++p) PASS();
    times[r] = (thread_cpu_s() - start) * 1e9 / (passes * STATES);
  }
  qsort(times, reps, sizeof(double), by_value);
  const char* name = strrchr(argv[1], '/') ? strrchr(argv[1], '/') + 1 : argv[1];
  printf("model,nq,nv,algo,median_ns,min_ns,max_ns,calls_per_rep\n");
  printf("%.*s,%d,%d,mj_forward,%.2f,%.2f,%.2f,%ld\n", (int)(strcspn(name, ".")), name, nq, nv,
         times[reps / 2], times[0], times[reps - 1], passes * STATES);
  fprintf(stderr, "checksum %g\n", sink);
  free(times); free(qpos); free(qvel); free(qfrc);
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}
