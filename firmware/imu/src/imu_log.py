"""Writes firmware/imu/src/imu_log.bin, the register table that firmware/imu/src/main.rs replays.

Source: BROAD trial 07 "undisturbed fast rotation B" (D. Laidig, M. Caruso, A. Cereatti,
T. Seel, "BROAD - A Benchmark for Robust Inertial Orientation Estimation", Data 6(7):72, 2021,
doi:10.3390/data6070072; CC BY 4.0), 285.714 Hz (3500 us). Rows 6700..10700 of the trial:
3.05 s of rest, then 10.95 s of hand-held rotation up to 1385 deg/s.

Each row is nine little-endian i16 registers, the trial's sample quantised to the chips
firmware/imu/src/main.rs drives (round to nearest, clamped to the i16 range):
- gyro x,y,z: ICM-42670 at +-2000 deg/s, 16.4 LSB per deg/s (datasheet table 1);
- accel x,y,z: ICM-42670 at +-4 g, 8192 LSB per g, g = 9.80665 m/s^2 (datasheet table 2);
- mag x,y,z: LSM303AGR magnetometer, 1.5 mgauss = 0.15 uT per LSB, in the chip's own axes,
  turned against the IMU's (chip x = IMU y, chip y = -IMU x, chip z = IMU z: the firmware's
  AxisRemap "-y,x,z" undoes it) plus a hard-iron offset HARD_IRON_UT (chip axes) that the
  firmware's MagnetometerCalibration removes. BROAD's field is already calibrated; the turn and
  the offset model a board where the magnetometer is a second chip.

Two of the three faults are written into the table (row numbers within the table;
firmware/imu/src/replay.rs documents the firmware's outcome for each):
- SATURATED_ROWS: gyro x at its positive full scale, +32767 (a shock driving the gyro to its rail);
- STUCK_ROWS: the IMU repeats the gyro and accelerometer registers of the first row of the range
  (a sensor whose output froze; the magnetometer, another chip, goes on).
The third fault, a missed data-ready, is a bus behaviour, not data: the device model in
firmware/imu/src/main.rs does not raise the status bit of one row (MISSED_DRDY_ROW in replay.rs).

The gyro bias printed at the end (mean of rows 0..6000 of the trial, at rest, before the table)
is the firmware's gyro calibration (GYRO_BIAS in replay.rs).

Run: python3 firmware/imu/src/imu_log.py ../shared/real-data/broad/07_undisturbed_fast_rotation_B.csv.gz
"""
import gzip
import math
import struct
import sys

START, ROWS = 6700, 4000
SATURATED_ROWS = range(1500, 1503)
STUCK_ROWS = range(2500, 2540)
HARD_IRON_UT = (12.0, -7.5, 4.5)
GYRO_LSB_PER_DPS = 16.4
ACCEL_LSB_PER_G = 8192.0
G = 9.80665
MAG_UT_PER_LSB = 0.15


def reg(x):
    return max(-32768, min(32767, int(math.floor(x + 0.5))))


def main(path, out):
    with gzip.open(path, "rt") as f:
        header = f.readline().strip().split(",")
        rows = [list(map(float, line.split(",")[:10])) for line in f]
    assert header[:10] == ["t_s", "gyr_x_rad_s", "gyr_y_rad_s", "gyr_z_rad_s", "acc_x_m_s2",
                           "acc_y_m_s2", "acc_z_m_s2", "mag_x_uT", "mag_y_uT", "mag_z_uT"]
    bias = [sum(r[1 + i] for r in rows[:6000]) / 6000 for i in range(3)]
    table = []
    for r in rows[START:START + ROWS]:
        gyro = [reg(math.degrees(w) * GYRO_LSB_PER_DPS) for w in r[1:4]]
        accel = [reg(a / G * ACCEL_LSB_PER_G) for a in r[4:7]]
        bx, by, bz = r[7:10]
        chip = (by, -bx, bz)
        mag = [reg((c + h) / MAG_UT_PER_LSB) for c, h in zip(chip, HARD_IRON_UT)]
        table.append(gyro + accel + mag)
    for k in SATURATED_ROWS:
        table[k][0] = 32767
    frozen = table[STUCK_ROWS[0]][:6]
    for k in STUCK_ROWS:
        table[k][:6] = frozen
    with open(out, "wb") as f:
        for row in table:
            f.write(struct.pack("<9h", *row))
    print(f"{out}: {len(table)} rows; gyro bias (rad/s) {bias[0]:.9e} {bias[1]:.9e} {bias[2]:.9e}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else "firmware/imu/src/imu_log.bin")
