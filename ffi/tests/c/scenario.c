/* The C test scenario of gyrostat's C interface: every function family on inputs that do not
 * repeat (a xorshift32 sequence), printed as hexadecimal bits, one line per result. The same
 * file runs on the host (host_main.c) and bare metal under QEMU (bare_main.c); ffi/tests/c_host.rs
 * computes the expected lines with the Rust API and compares them with both outputs. */
#include <stddef.h>
#include <stdint.h>

#include "gyrostat.h"
#include "scenario.h"

static scenario_put_fn put;
static uint32_t rng = 0x9E3779B9u;

static uint32_t next_u32(void) {
  rng ^= rng << 13;
  rng ^= rng >> 17;
  rng ^= rng << 5;
  return rng;
}

/* Uniform in [-1, 1): a signed 32-bit integer times 2^-31 (exact after the conversion's
 * rounding, the same in C and Rust). */
static float rnd_f32(void) { return (float)(int32_t)next_u32() * 4.656612873077393e-10f; }
static double rnd_f64(void) { return (double)(int32_t)next_u32() * 4.656612873077393e-10; }


/* Random vectors and quaternions drawn component by component, in order (the expressions of a C
 * initializer list are not sequenced). `c + s·u` with u uniform in [-1, 1). */
static gyro_vec3_f32 vec32(float s, float cx, float cy, float cz) {
  gyro_vec3_f32 v;
  v.x = cx + rnd_f32() * s;
  v.y = cy + rnd_f32() * s;
  v.z = cz + rnd_f32() * s;
  return v;
}

static gyro_vec3_f64 vec64(double s, double cx, double cy, double cz) {
  gyro_vec3_f64 v;
  v.x = cx + rnd_f64() * s;
  v.y = cy + rnd_f64() * s;
  v.z = cz + rnd_f64() * s;
  return v;
}

static gyro_quat_f32 quat32(void) {
  gyro_quat_f32 q;
  q.w = rnd_f32();
  q.x = rnd_f32();
  q.y = rnd_f32();
  q.z = rnd_f32();
  return q;
}

static gyro_quat_f64 quat64(void) {
  gyro_quat_f64 q;
  q.w = rnd_f64();
  q.x = rnd_f64();
  q.y = rnd_f64();
  q.z = rnd_f64();
  return q;
}

/* A raw 16-bit gyro register: the top 12 bits of a draw (|raw| < 2048). */
static int16_t raw16(void) { return (int16_t)((int32_t)next_u32() >> 20); }

static char line[256];
static size_t len;

static void begin(const char *label) {
  len = 0;
  while (*label && len < sizeof line - 40) line[len++] = *label++;
}

static void hex(uint64_t v, int digits) {
  static const char d[] = "0123456789abcdef";
  line[len++] = ' ';
  for (int i = digits - 1; i >= 0; i--) line[len++] = d[(v >> (4 * i)) & 0xF];
}

static void end(void) {
  line[len++] = '\n';
  line[len] = 0;
  put(line);
}

static uint32_t bits32(float x) {
  union { float f; uint32_t u; } c = {x};
  return c.u;
}

static uint64_t bits64(double x) {
  union { double f; uint64_t u; } c = {x};
  return c.u;
}

static void flush_if_full(void) {
  if (len > sizeof line - 40) {
    end();
    begin("+");
  }
}

static void f32s(const float *x, int n) {
  for (int i = 0; i < n; i++) {
    flush_if_full();
    hex(bits32(x[i]), 8);
  }
}

static void f64s(const double *x, int n) {
  for (int i = 0; i < n; i++) {
    flush_if_full();
    hex(bits64(x[i]), 16);
  }
}

static void status_line(const char *label, gyro_status s) {
  begin(label);
  hex((uint32_t)s, 2);
  end();
}

/* A status and, on success, n floats of the output. */
static void out32(const char *label, gyro_status s, const void *p, int n) {
  begin(label);
  hex((uint32_t)s, 2);
  if (s == GYRO_OK) f32s((const float *)p, n);
  end();
}

static void out64(const char *label, gyro_status s, const void *p, int n) {
  begin(label);
  hex((uint32_t)s, 2);
  if (s == GYRO_OK) f64s((const double *)p, n);
  end();
}

static void euler32(const char *label, gyro_status s, const gyro_euler_f32 *e) {
  begin(label);
  hex((uint32_t)s, 2);
  if (s == GYRO_OK) {
    f32s(e->angles, 3);
    f32s(&e->distance_to_pole, 1);
    hex((uint32_t)e->gimbal_lock, 8);
    f32s(&e->sign, 1);
    f32s(&e->combined_angle, 1);
  }
  end();
}

static void euler64(const char *label, gyro_status s, const gyro_euler_f64 *e) {
  begin(label);
  hex((uint32_t)s, 2);
  if (s == GYRO_OK) {
    f64s(e->angles, 3);
    f64s(&e->distance_to_pole, 1);
    hex((uint32_t)e->gimbal_lock, 8);
    f64s(&e->sign, 1);
    f64s(&e->combined_angle, 1);
  }
  end();
}

/* State structs in static storage (.bss, zero at start), as firmware allocates them. */
static gyro_increment_integrator_f32 inc32, inc32c;
static gyro_increment_integrator_f64 inc64;
static gyro_increment_integrator_q30 inc30;
static gyro_increment_quantizer_q30 quant;
static gyro_rate_integrator_f32 rate32;
static gyro_rate_integrator_f64 rate64;
static gyro_gyrostat_f32 body32;
static gyro_gyrostat_f64 body64;
static gyro_estimator_f32 est32;
#ifndef GYRO_SCENARIO_NO_F64_ESTIMATOR
static gyro_estimator_f64 est64;
#endif

static void rotations(void) {
  for (int k = 0; k < 6; k++) {
    const gyro_quat_f32 r32 = quat32();
    const gyro_quat_f64 r64 = quat64();
    const gyro_vec3_f32 v32 = vec32(1.0f, 0, 0, 0);
    const gyro_vec3_f64 v64 = vec64(1.0, 0, 0, 0);
    gyro_quat_f32 q32 = {1, 0, 0, 0}, p32 = {1, 0, 0, 0};
    gyro_quat_f64 q64 = {1, 0, 0, 0}, p64 = {1, 0, 0, 0};
    gyro_vec3_f32 w32;
    gyro_vec3_f64 w64;
    gyro_mat3_f32 m32;
    gyro_mat3_f64 m64;
    gyro_euler_f32 e32;
    gyro_euler_f64 e64;
    out32("normalize32", gyro_quat_normalize_f32(&r32, &q32), &q32, 4);
    out64("normalize64", gyro_quat_normalize_f64(&r64, &q64), &q64, 4);
    out32("dcm32", gyro_quat_to_dcm_f32(&q32, &m32), &m32, 9);
    out64("dcm64", gyro_quat_to_dcm_f64(&q64, &m64), &m64, 9);
    out32("from_dcm32", gyro_quat_from_dcm_f32(&m32, 1e-5f, &p32), &p32, 4);
    out64("from_dcm64", gyro_quat_from_dcm_f64(&m64, 1e-12, &p64), &p64, 4);
    out32("rotvec32", gyro_quat_to_rotvec_f32(&q32, &w32), &w32, 3);
    out64("rotvec64", gyro_quat_to_rotvec_f64(&q64, &w64), &w64, 3);
    out32("from_rotvec32", gyro_quat_from_rotvec_f32(&v32, &p32), &p32, 4);
    out64("from_rotvec64", gyro_quat_from_rotvec_f64(&v64, &p64), &p64, 4);
    out32("axis_angle32", gyro_quat_from_axis_angle_f32(&v32, rnd_f32() * 3.0f, &p32), &p32, 4);
    out64("axis_angle64", gyro_quat_from_axis_angle_f64(&v64, rnd_f64() * 3.0, &p64), &p64, 4);
    out32("mul32", gyro_quat_mul_f32(&q32, &p32, &p32), &p32, 4);
    out64("mul64", gyro_quat_mul_f64(&q64, &p64, &p64), &p64, 4);
    out32("rotate32", gyro_quat_rotate_f32(&q32, &v32, &w32), &w32, 3);
    out64("rotate64", gyro_quat_rotate_f64(&q64, &v64, &w64), &w64, 3);
    euler32("euler_ZYX32", gyro_quat_to_euler_f32(&q32, "ZYX", GYRO_GIMBAL_ZERO_THIRD, NULL, &e32), &e32);
    euler64("euler_zxz64", gyro_quat_to_euler_f64(&q64, "zxz", GYRO_GIMBAL_ZERO_FIRST, NULL, &e64), &e64);
    out32("from_euler32", gyro_quat_from_euler_f32("ZYX", &e32.angles, &p32), &p32, 4);
    out64("from_euler64", gyro_quat_from_euler_f64("zxz", &e64.angles, &p64), &p64, 4);
  }
  /* Gimbal lock: pitch exactly +pi/2 (ZYX), and the lower pole of a proper sequence. */
  {
    const float a32[3] = {0.3f, 1.57079632679489661923f, 0.1f};
    const double a64[3] = {-2.5, 0.0, 0.7};
    const double prev[3] = {0.5, 0.0, 0.0};
    gyro_quat_f32 q32;
    gyro_quat_f64 q64;
    gyro_euler_f32 e32;
    gyro_euler_f64 e64;
    out32("lock_q32", gyro_quat_from_euler_f32("ZYX", &a32, &q32), &q32, 4);
    euler32("lock32", gyro_quat_to_euler_f32(&q32, "ZYX", GYRO_GIMBAL_ZERO_THIRD, NULL, &e32), &e32);
    out64("lock_q64", gyro_quat_from_euler_f64("ZYZ", &a64, &q64), &q64, 4);
    euler64("lock64", gyro_quat_to_euler_f64(&q64, "ZYZ", GYRO_GIMBAL_CLOSEST_TO, &prev, &e64), &e64);
  }
  /* Bad input: typed statuses, never a crash. */
  {
    gyro_quat_f32 zero = {0, 0, 0, 0}, q = {1, 0, 0, 0};
    gyro_quat_f64 nan = {0.0 / 0.0, 0, 0, 0}, q64;
    gyro_mat3_f64 reflection = {{{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    gyro_euler_f32 e;
    gyro_increment_integrator_f32 never_initialized = {0};
    gyro_vec3_f32 d = {0, 0, 0};
    status_line("err_zero_norm", gyro_quat_normalize_f32(&zero, &q));
    status_line("err_non_finite", gyro_quat_normalize_f64(&nan, &q64));
    status_line("err_null_in", gyro_quat_normalize_f32(NULL, &q));
    status_line("err_null_out", gyro_quat_normalize_f64(&q64, NULL));
    status_line("err_reflection", gyro_quat_from_dcm_f64(&reflection, 1e-9, &q64));
    status_line("err_sequence", gyro_quat_to_euler_f32(&q, "ZZX", GYRO_GIMBAL_ZERO_THIRD, NULL, &e));
    status_line("err_short_sequence", gyro_quat_to_euler_f32(&q, "ZY", GYRO_GIMBAL_ZERO_THIRD, NULL, &e));
    status_line("err_policy", gyro_quat_to_euler_f32(&q, "ZYX", 7, NULL, &e));
    status_line("err_closest_null", gyro_quat_to_euler_f32(&q, "ZYX", GYRO_GIMBAL_CLOSEST_TO, NULL, &e));
    status_line("err_uninitialized", gyro_increment_integrator_f32_push(&never_initialized, &d, NULL, NULL));
    status_line("err_rule", gyro_increment_integrator_f32_init(&inc32, &q, 9, GYRO_NORM_FAST, 0));
  }
}

static void increments(void) {
  const gyro_quat_f32 id32 = {1, 0, 0, 0};
  const gyro_quat_f64 id64 = {1, 0, 0, 0};
  const gyro_quat_q30 id30 = {1 << 30, 0, 0, 0};
  status_line("inc32_init", gyro_increment_integrator_f32_init(&inc32, &id32, GYRO_CONING_TWO_SAMPLE, GYRO_NORM_FAST, 0));
  status_line("inc32c_init", gyro_increment_integrator_f32_init(&inc32c, &id32, GYRO_CONING_THREE_SAMPLE, GYRO_NORM_FAST, 1));
  status_line("inc64_init", gyro_increment_integrator_f64_init(&inc64, &id64, GYRO_CONING_FOUR_SAMPLE, GYRO_NORM_EXACT, 0));
  status_line("inc30_init", gyro_increment_integrator_q30_init(&inc30, &id30, GYRO_CONING_TWO_SAMPLE, GYRO_NORM_FAST));
  status_line("quant_init", gyro_increment_quantizer_q30_init(&quant, 1.0653e-6));
  uint32_t n32 = 0, n32c = 0, n64 = 0, n30 = 0;
  for (int k = 1; k <= 203; k++) {
    const gyro_vec3_f32 d32 = vec32(0x1p-8f, 0, 0, 0);
    const gyro_vec3_f64 d64 = vec64(0x1p-8, 0, 0, 0);
    int16_t raw[3];
    raw[0] = raw16();
    raw[1] = raw16();
    raw[2] = raw16();
    gyro_vec3_q30 d30;
    gyro_quat_f32 q32, q32c;
    gyro_quat_f64 q64;
    gyro_quat_q30 q30;
    uint32_t u;
    gyro_status s;
    if ((s = gyro_increment_integrator_f32_push(&inc32, &d32, &u, &q32)) != GYRO_OK) status_line("inc32_push", s);
    n32 += u;
    if ((s = gyro_increment_integrator_f32_push(&inc32c, &d32, &u, &q32c)) != GYRO_OK) status_line("inc32c_push", s);
    n32c += u;
    if ((s = gyro_increment_integrator_f64_push(&inc64, &d64, &u, &q64)) != GYRO_OK) status_line("inc64_push", s);
    n64 += u;
    if ((s = gyro_increment_quantizer_q30_quantize(&quant, &raw, &d30)) != GYRO_OK) status_line("quant", s);
    if ((s = gyro_increment_integrator_q30_push(&inc30, &d30, &u, &q30)) != GYRO_OK) status_line("inc30_push", s);
    n30 += u;
    if (k % 50 == 0) {
      out32("inc32", GYRO_OK, &q32, 4);
      out32("inc32c", GYRO_OK, &q32c, 4);
      out64("inc64", GYRO_OK, &q64, 4);
      begin("inc30");
      hex((uint32_t)q30.w, 8), hex((uint32_t)q30.x, 8), hex((uint32_t)q30.y, 8), hex((uint32_t)q30.z, 8);
      hex((uint32_t)d30.x, 8), hex((uint32_t)d30.y, 8), hex((uint32_t)d30.z, 8);
      end();
    }
  }
  begin("inc_updates");
  hex(n32, 8), hex(n32c, 8), hex(n64, 8), hex(n30, 8);
  end();
  gyro_quat_f32 q32;
  gyro_quat_f64 q64;
  out32("inc32_provisional", gyro_increment_integrator_f32_attitude(&inc32, 1, &q32), &q32, 4);
  out32("inc32c_flush", gyro_increment_integrator_f32_flush(&inc32c, &q32), &q32, 4);
  out64("inc64_flush", gyro_increment_integrator_f64_flush(&inc64, &q64), &q64, 4);
  {
    gyro_vec3_f32 big = {4.0f, 0, 0};
    gyro_vec3_q30 big30 = {1 << 28, 0, 0};
    status_line("err_step_too_long", gyro_increment_integrator_f32_push(&inc32, &big, NULL, NULL));
    status_line("err_q30_range", gyro_increment_integrator_q30_push(&inc30, &big30, NULL, NULL));
  }
}

static void rates(void) {
  const gyro_quat_f32 id32 = {1, 0, 0, 0};
  const gyro_quat_f64 id64 = {1, 0, 0, 0};
  status_line("rate32_init", gyro_rate_integrator_f32_init(&rate32, &id32, GYRO_RATE_MAGNUS4, GYRO_NORM_FAST, 0.01f, 0));
  status_line("rate64_init", gyro_rate_integrator_f64_init(&rate64, &id64, GYRO_RATE_CF4, GYRO_NORM_EXACT, 0.01, 1));
  uint32_t total32 = 0, total64 = 0;
  for (int k = 0; k < 101; k++) {
    const gyro_vec3_f32 w32 = vec32(2.0f, 0, 0, 0);
    const gyro_vec3_f64 w64 = vec64(2.0, 0, 0, 0);
    gyro_quat_f32 o32[3];
    gyro_quat_f64 o64[3];
    uint32_t c32 = 0, c64 = 0;
    gyro_status s;
    if ((s = gyro_rate_integrator_f32_push(&rate32, &w32, &o32, &c32)) != GYRO_OK) status_line("rate32_push", s);
    if ((s = gyro_rate_integrator_f64_push(&rate64, &w64, &o64, &c64)) != GYRO_OK) status_line("rate64_push", s);
    total32 += c32;
    total64 += c64;
    if (k % 25 == 0 && c32 > 0) out32("rate32", GYRO_OK, &o32[c32 - 1], 4);
    if (k % 25 == 0 && c64 > 0) out64("rate64", GYRO_OK, &o64[c64 - 1], 4);
  }
  gyro_quat_f32 o32[3];
  gyro_quat_f64 o64[3];
  uint32_t c32 = 0, c64 = 0;
  out32("rate32_finish", gyro_rate_integrator_f32_finish(&rate32, &o32, &c32), &o32[c32 ? c32 - 1 : 0], c32 ? 4 : 0);
  out64("rate64_finish", gyro_rate_integrator_f64_finish(&rate64, &o64, &c64), &o64[c64 ? c64 - 1 : 0], c64 ? 4 : 0);
  begin("rate_counts");
  hex(total32 + c32, 8), hex(total64 + c64, 8);
  end();
  gyro_quat_f32 q;
  status_line("err_finished", gyro_rate_integrator_f32_attitude(&rate32, &q));
}

static void bodies(void) {
  const gyro_vec3_f64 diag64 = {6.0, 4.0, 3.0}, off64 = {0.05, -0.02, 0.01};
  const gyro_wheel_f64 wheel = {{0.0, 1.0, 0.0}, 0.05};
  const gyro_vec3_f32 diag32 = {2.0f, 3.0f, 4.5f};
  const gyro_quat_f64 q64 = {1, 0, 0, 0};
  const gyro_quat_f32 q32 = {1, 0, 0, 0};
  const gyro_vec3_f64 w64 = {0.05, 1.0, 0.01};
  const gyro_vec3_f32 w32 = {0.3f, -0.2f, 0.9f};
  const double speeds[GYRO_MAX_WHEELS] = {60.0, 0, 0, 0};
  gyro_gyrostat_state_f64 s64;
  gyro_gyrostat_state_f32 s32;
  status_line("body64_init", gyro_gyrostat_f64_init(&body64, &diag64, &off64, &wheel, 1));
  status_line("body32_init", gyro_gyrostat_f32_init(&body32, &diag32, NULL, NULL, 0));
  out64("body64_state", gyro_gyrostat_f64_state_from_omega(&body64, &q64, &w64, &speeds, &s64), &s64, 11);
  out32("body32_state", gyro_gyrostat_f32_state_from_omega(&body32, &q32, &w32, NULL, &s32), &s32, 11);
  for (int k = 0; k < 100; k++) {
    const gyro_vec3_f64 tau = vec64(0.01, 0, 0, 0);
    const double wt[GYRO_MAX_WHEELS] = {rnd_f64() * 0.02, 0, 0, 0};
    gyro_status s = gyro_gyrostat_f64_step(&body64, GYRO_INTEGRATOR_YOSHIDA4, &s64, 0.01 * k, 0.01, &tau, &wt, &s64);
    if (s != GYRO_OK) status_line("body64_step", s);
    s = gyro_gyrostat_f32_step(&body32, GYRO_INTEGRATOR_RK4, &s32, 0.02f * (float)k, 0.02f, NULL, NULL, &s32);
    if (s != GYRO_OK) status_line("body32_step", s);
    if (k % 33 == 0) {
      out64("body64", GYRO_OK, &s64, 11);
      out32("body32", GYRO_OK, &s32, 11);
    }
  }
  out64("body64_end", GYRO_OK, &s64, 11);
  out32("body32_end", GYRO_OK, &s32, 11);
  {
    const gyro_vec3_f64 bad = {1.0, 1.0, 3.0};
    const gyro_wheel_f64 wheels5[5] = {wheel, wheel, wheel, wheel, wheel};
    gyro_gyrostat_f64 b;
    status_line("err_inertia", gyro_gyrostat_f64_init(&b, &bad, NULL, NULL, 0));
    status_line("err_wheels", gyro_gyrostat_f64_init(&b, &diag64, NULL, wheels5, 5));
    status_line("err_dt", gyro_gyrostat_f64_step(&body64, GYRO_INTEGRATOR_STRANG, &s64, 0.0, -0.01, NULL, NULL, &s64));
  }
}

static void estimators(void) {
  /* f32 from a parameter struct: the defaults with a gyro range that some samples reach and
   * the CF4 rate rule. */
  gyro_estimator_params_f32 params;
  status_line("est32_params", gyro_estimator_f32_default_params(&params));
  params.gyro_range = 0.24f;
  params.rate_rule = GYRO_RATE_RULE_CF4;
  status_line("est32_init", gyro_estimator_f32_init_params(&est32, &params));
#ifndef GYRO_SCENARIO_NO_F64_ESTIMATOR
  status_line("est64_init", gyro_estimator_f64_init(&est64, GYRO_FRAME_NED));
  gyro_estimator_outcome o64 = {0};
#endif
  gyro_estimator_outcome o32 = {0};
  uint32_t saturated = 0;
  for (int k = 0; k < 300; k++) {
    const gyro_vec3_f32 g32 = vec32(0.05f, 0, 0, 0.2f);
    const gyro_vec3_f32 a32 = vec32(0.1f, 0, 0.5f, 9.8f);
    const gyro_vec3_f64 g64 = vec64(0.05, 0, 0.1, 0);
    const gyro_vec3_f64 a64 = vec64(0.1, 0.3, 0, -9.8);
    const gyro_vec3_f64 m64 = vec64(1.0, 20.0, 1.0, 40.0);
    gyro_status s = gyro_estimator_f32_update(&est32, &g32, &a32, NULL, 0.01f, &o32);
    if (s != GYRO_OK) status_line("est32_update", s);
    saturated += o32.gyro_saturated;
#ifndef GYRO_SCENARIO_NO_F64_ESTIMATOR
    s = gyro_estimator_f64_update(&est64, &g64, &a64, &m64, 0.01, &o64);
    if (s != GYRO_OK) status_line("est64_update", s);
#else
    (void)g64, (void)a64, (void)m64; /* drawn all the same: the random sequence stays the host's */
#endif
    if (k % 100 == 99) {
      gyro_quat_f32 q32;
      gyro_vec3_f32 b32;
      out32("est32", gyro_estimator_f32_attitude(&est32, &q32, &b32), &q32, 4);
      out32("est32_bias", GYRO_OK, &b32, 3);
#ifndef GYRO_SCENARIO_NO_F64_ESTIMATOR
      gyro_quat_f64 q64;
      gyro_vec3_f64 b64;
      out64("est64", gyro_estimator_f64_attitude(&est64, &q64, &b64), &q64, 4);
      out64("est64_bias", GYRO_OK, &b64, 3);
#endif
      begin("est_outcome");
      hex(o32.gyro_saturated, 1), hex(o32.accel, 1), hex(o32.mag, 1), hex(o32.at_rest, 1), hex(o32.initialized, 1);
#ifndef GYRO_SCENARIO_NO_F64_ESTIMATOR
      hex(o64.gyro_saturated, 1), hex(o64.accel, 1), hex(o64.mag, 1), hex(o64.at_rest, 1), hex(o64.initialized, 1);
#endif
      end();
    }
  }
  begin("est32_saturated");
  hex(saturated, 8);
  end();
  {
    const gyro_vec3_f32 g = {0, 0, 0}, a = {0, 0, 0};
    gyro_estimator_outcome o;
    status_line("zero_accel", gyro_estimator_f32_update(&est32, &g, &a, NULL, 0.01f, &o));
    begin("zero_accel_outcome");
    hex(o.accel, 1);
    end();
    status_line("err_est_dt", gyro_estimator_f32_update(&est32, &g, &a, NULL, 0.0f, &o));
  }
}

/* The sensor front end: the clocks' intervals, the clip guard, the raw scale, the calibrations
 * and the axis remap. */
static gyro_sample_clock_f32 clock32;
static gyro_sample_clock_f64 clock64;
static gyro_micros_clock clock_us;
static gyro_clip_guard guard;
static gyro_inertial_calibration_f32 cal32;
#ifndef GYRO_SCENARIO_NO_F64_ESTIMATOR
static gyro_inertial_calibration_f64 cal64;
#endif
static gyro_mag_calibration_f32 mcal32;
#ifndef GYRO_SCENARIO_NO_F64_ESTIMATOR
static gyro_mag_calibration_f64 mcal64;
#endif
static gyro_axis_remap remap;

static void interval_line(const char *label, gyro_status s, uint32_t kind, uint64_t dt, int digits) {
  begin(label);
  hex((uint32_t)s, 2);
  if (s == GYRO_OK) hex(kind, 1), hex(dt, digits);
  end();
}

static void sensors(void) {
  status_line("clock_bad_nominal", gyro_sample_clock_f64_init(&clock64, 0.0, 5.0));
  status_line("clock_bad_factor", gyro_sample_clock_f32_init(&clock32, 0.01f, 0.5f));
  status_line("clock64_init", gyro_sample_clock_f64_init(&clock64, 0.01, 5.0));
  status_line("clock32_init", gyro_sample_clock_f32_init(&clock32, 0.01f, 5.0f));
  {
    /* first, steps with jitter, a repeat, a backwards stamp, a gap, a non-finite stamp */
    double t64 = 100.0 + rnd_f64();
    float t32 = 100.0f + rnd_f32();
    for (int k = 0; k < 8; k++) {
      double d64 = 0.01 + 0.002 * rnd_f64();
      float d32 = 0.01f + 0.002f * rnd_f32();
      if (k == 3) d64 = 0.0, d32 = 0.0f;
      if (k == 4) d64 = -0.003, d32 = -0.003f;
      if (k == 6) d64 = 0.25, d32 = 0.25f;
      uint32_t kind = 0;
      double dt64 = 0;
      float dt32 = 0;
      gyro_status s = gyro_sample_clock_f64_interval(&clock64, t64 + d64, &kind, &dt64);
      interval_line("clock64", s, kind, bits64(dt64), 16);
      s = gyro_sample_clock_f32_interval(&clock32, t32 + d32, &kind, &dt32);
      interval_line("clock32", s, kind, bits32(dt32), 8);
      if (k != 3 && k != 4) t64 += d64, t32 += d32;
    }
    uint32_t kind;
    double dt;
    union { uint64_t u; double f; } nan = {0x7ff8000000000000u};
    status_line("clock64_nan", gyro_sample_clock_f64_interval(&clock64, nan.f, &kind, &dt));
    status_line("clock64_restart", gyro_sample_clock_f64_restart(&clock64, 0, 0.0));
    gyro_status s = gyro_sample_clock_f64_interval(&clock64, t64, &kind, &dt);
    interval_line("clock64_first", s, kind, bits64(dt), 16);
  }
  status_line("us_bad", gyro_micros_clock_init(&clock_us, 0, 5));
  status_line("us_init", gyro_micros_clock_init(&clock_us, 10000, 5));
  {
    uint32_t t = 0xFFFFFFFFu - 25000u;
    for (int k = 0; k < 6; k++) {
      uint32_t d = 9000u + (next_u32() >> 20);
      if (k == 2) d = 0;
      if (k == 3) d = 0xFFFFFFFFu - 99u; /* 100 us backwards */
      if (k == 4) d = 80000u;
      uint32_t kind = 0, dt = 0;
      gyro_status s = gyro_micros_clock_interval(&clock_us, t + d, &kind, &dt);
      interval_line("us", s, kind, dt, 8);
      if (k != 2 && k != 3) t += d;
    }
  }
  status_line("clip_bad", gyro_clip_guard_init(&guard, 0, GYRO_CLIP_PASS));
  status_line("clip_init", gyro_clip_guard_init(&guard, 30000, GYRO_CLIP_HOLD_LAST));
  for (int k = 0; k < 5; k++) {
    gyro_vec3_i16 r, o;
    r.x = raw16(), r.y = raw16(), r.z = raw16();
    if (k == 2) r.x = 32767, r.z = -32768;
    if (k == 3) r.y = 30000;
    uint32_t clipped = 0;
    gyro_status s = gyro_clip_guard_filter(&guard, &r, &o, &clipped);
    begin("clip");
    hex((uint32_t)s, 2);
    hex((uint16_t)o.x, 4), hex((uint16_t)o.y, 4), hex((uint16_t)o.z, 4), hex(clipped, 1);
    end();
    gyro_vec3_f32 v32;
    gyro_vec3_f64 v64;
    out32("raw32", gyro_raw_scale_f32(&o, 0.00106526f, &v32), &v32, 3);
    out64("raw64", gyro_raw_scale_f64(&o, 0.00106526, &v64), &v64, 3);
  }
  status_line("clip_reject_init", gyro_clip_guard_init(&guard, 1000, GYRO_CLIP_REJECT));
  {
    const gyro_vec3_i16 r = {5, -1000, 7};
    gyro_vec3_i16 o;
    status_line("clip_reject", gyro_clip_guard_filter(&guard, &r, &o, NULL));
  }
  {
    gyro_mat3_f32 m32;
    gyro_mat3_f64 m64;
    for (int i = 0; i < 3; i++) {
      for (int j = 0; j < 3; j++) {
        m32.m[i][j] = (i == j ? 1.0f : 0.0f) + 0.01f * rnd_f32();
        m64.m[i][j] = (i == j ? 1.0 : 0.0) + 0.01 * rnd_f64();
      }
    }
    const gyro_vec3_f32 s32 = vec32(0.02f, 1, 1, 1), b32 = vec32(0.01f, 0, 0, 0);
    const gyro_vec3_f64 s64 = vec64(0.02, 1, 1, 1), b64 = vec64(0.01, 0, 0, 0);
    status_line("cal32_init", gyro_inertial_calibration_f32_init(&cal32, &m32, &s32, &b32));
    status_line("mcal32_init", gyro_mag_calibration_f32_init(&mcal32, &m32, &b32));
#ifndef GYRO_SCENARIO_NO_F64_ESTIMATOR
    status_line("cal64_init", gyro_inertial_calibration_f64_init(&cal64, &m64, &s64, &b64));
    status_line("mcal64_init", gyro_mag_calibration_f64_init(&mcal64, &m64, &b64));
#else
    (void)m64, (void)s64, (void)b64; /* drawn all the same: the random sequence stays the host's */
#endif
    const gyro_vec3_f32 bad_scale = {1, -1, 1};
    status_line("cal32_bad", gyro_inertial_calibration_f32_init(&cal32, &m32, &bad_scale, &b32));
    for (int k = 0; k < 3; k++) {
      const gyro_vec3_f32 r32 = vec32(2.0f, 0, 0, 0);
      const gyro_vec3_f64 r64 = vec64(2.0, 0, 0, 0);
      gyro_vec3_f32 o32;
      gyro_vec3_f64 o64;
      out32("cal32", gyro_inertial_calibration_f32_apply(&cal32, &r32, &o32), &o32, 3);
      out32("mcal32", gyro_mag_calibration_f32_apply(&mcal32, &r32, &o32), &o32, 3);
#ifndef GYRO_SCENARIO_NO_F64_ESTIMATOR
      out64("cal64", gyro_inertial_calibration_f64_apply(&cal64, &r64, &o64), &o64, 3);
      out64("mcal64", gyro_mag_calibration_f64_apply(&mcal64, &r64, &o64), &o64, 3);
#else
      (void)r64, (void)o64;
#endif
    }
  }
  {
    const uint32_t twice[3] = {0, 0, 1}, none[3] = {0, 0, 0}, flip[3] = {1, 0, 0};
    const uint32_t source[3] = {2, 0, 1}, negate[3] = {0, 1, 1}, straight[3] = {0, 1, 2};
    status_line("remap_twice", gyro_axis_remap_init(&remap, twice, none));
    status_line("remap_reflection", gyro_axis_remap_init(&remap, straight, flip));
    status_line("remap_init", gyro_axis_remap_init(&remap, source, negate));
    const gyro_vec3_f32 v32 = vec32(1.0f, 0, 0, 0);
    const gyro_vec3_f64 v64 = vec64(1.0, 0, 0, 0);
    gyro_vec3_f32 o32;
    gyro_vec3_f64 o64;
    out32("remap32", gyro_axis_remap_apply_f32(&remap, &v32, &o32), &o32, 3);
    out64("remap64", gyro_axis_remap_apply_f64(&remap, &v64, &o64), &o64, 3);
  }
}

void scenario_run(scenario_put_fn put_line) {
  put = put_line;
  rotations();
  increments();
  rates();
  bodies();
  estimators();
  sensors();
  put("done\n");
}
