/* A stand-in for NVIDIA's libnvidia-ml.so.1 (tests/measurement_test.cpp,
   through OIT_NVML_LIBRARY): one device whose SM clock rises by 30% at every
   read, a fixed memory clock and temperature. */
static unsigned sm_clock = 1000;

int nvmlInit_v2(void) { return 0; }
int nvmlShutdown(void) { return 0; }
int nvmlDeviceGetHandleByIndex_v2(unsigned index, void** device) {
  static int the_device;
  if (index != 0) return 2;
  *device = &the_device;
  return 0;
}
int nvmlDeviceGetClockInfo(void* device, int type, unsigned* mhz) {
  (void)device;
  if (type == 1) {
    *mhz = sm_clock;
    sm_clock = sm_clock * 13 / 10;
  } else {
    *mhz = 2619;
  }
  return 0;
}
int nvmlDeviceGetTemperature(void* device, int sensor, unsigned* celsius) {
  (void)device;
  (void)sensor;
  *celsius = 41;
  return 0;
}
