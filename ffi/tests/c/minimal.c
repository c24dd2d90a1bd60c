/* The smallest useful C firmware for the footprint measurement (ffi/tests/c/footprint.sh): the
 * f32 2-sample increment integrator and the ZYX Euler angles with the gimbal lock, the C
 * counterpart of the `gyro2_euler` row of BENCHMARKS.md's footprint table. Linked with
 * bare_main.c in place of scenario.c; runs under QEMU and prints one line. */
#include <stddef.h>
#include <stdint.h>

#include "gyrostat.h"
#include "scenario.h"

static gyro_increment_integrator_f32 imu;

/* Opaque to the optimiser, as the Rust footprint probe's black_box operands. */
static volatile float increment = 1e-3f;

void scenario_run(scenario_put_fn put) {
  const gyro_quat_f32 q0 = {1.0f, 0.0f, 0.0f, 0.0f};
  gyro_quat_f32 q = q0;
  gyro_euler_f32 e;
  uint32_t updated = 0;
  int ok = gyro_increment_integrator_f32_init(&imu, &q0, GYRO_CONING_TWO_SAMPLE, GYRO_NORM_FAST, 0) == GYRO_OK;
  for (int k = 0; k < 2000; k++) {
    const gyro_vec3_f32 d = {0.0f, 0.0f, increment};
    ok &= gyro_increment_integrator_f32_push(&imu, &d, &updated, &q) == GYRO_OK;
  }
  ok &= gyro_quat_to_euler_f32(&q, "ZYX", GYRO_GIMBAL_ZERO_THIRD, NULL, &e) == GYRO_OK;
  /* 2000 increments of 1 mrad about z: yaw 2 rad. */
  ok &= e.angles[0] > 1.999f && e.angles[0] < 2.001f && e.gimbal_lock == 0;
  put(ok ? "minimal ok\n" : "minimal FAILED\n");
  if (ok) put("done\n");
}
