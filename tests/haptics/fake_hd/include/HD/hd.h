/* A fake of the OpenHaptics HD API for filum's tests (tests/haptics/openhaptics_device_test.cpp):
   the declarations filum's backend uses, with their documented types and units (lengths in mm,
   forces in N), and a control interface (fake_hd_control.h) through which a test plays the
   device and the scheduler. Written for filum from the API's documentation; not the SDK's
   header, whose enum values it does not share (the backend never depends on them). */
#ifndef FILUM_FAKE_HD_H
#define FILUM_FAKE_HD_H

#ifdef __cplusplus
extern "C" {
#endif

typedef unsigned int HHD;
typedef unsigned int HDenum;
typedef unsigned int HDerror;
typedef int HDint;
typedef long HDlong;
typedef unsigned long HDulong;
typedef unsigned short HDushort;
typedef double HDdouble;
typedef float HDfloat;
typedef unsigned char HDboolean;
typedef const char* HDstring;
typedef unsigned long HDSchedulerHandle;
typedef unsigned int HDCallbackCode;

typedef struct {
  HDerror errorCode;
  int internalErrorCode;
  HHD hHD;
} HDErrorInfo;

#define HDCALLBACK
#define HD_DEFAULT_DEVICE ((HDstring)0)
#define HD_INVALID_HANDLE ((HHD)0xFFFFFFFF)
#define HD_SUCCESS 0x0000
#define HD_DEVICE_ERROR(X) (((X).errorCode) != HD_SUCCESS)
#define HD_CALLBACK_DONE 0
#define HD_CALLBACK_CONTINUE 1
#define HD_MAX_SCHEDULER_PRIORITY 0xffff
#define HD_DEFAULT_SCHEDULER_PRIORITY 0x7fff

/* Error codes the fake raises. */
#define HD_DEVICE_FAULT 0x0101
#define HD_INVALID_OPERATION 0x0102
#define HD_ILLEGAL_BEGIN 0x0103

/* Parameters and capabilities. */
#define HD_CURRENT_BUTTONS 0x2000
#define HD_CURRENT_POSITION 0x2050
#define HD_CURRENT_VELOCITY 0x2051
#define HD_CURRENT_FORCE 0x2700
#define HD_CURRENT_GIMBAL_ANGLES 0x2150
#define HD_CURRENT_GIMBAL_TORQUE 0x2704
#define HD_OUTPUT_DOF 0x2554
#define HD_NOMINAL_MAX_TORQUE_FORCE 0x2622
#define HD_NOMINAL_MAX_STIFFNESS 0x2503
#define HD_NOMINAL_MAX_FORCE 0x2603
#define HD_NOMINAL_MAX_CONTINUOUS_FORCE 0x2604
#define HD_USABLE_WORKSPACE_DIMENSIONS 0x2551
#define HD_FORCE_OUTPUT 0x4000

typedef HDCallbackCode (HDCALLBACK* HDSchedulerCallback)(void* pUserData);

HHD hdInitDevice(HDstring pConfigName);
void hdDisableDevice(HHD hHD);
void hdBeginFrame(HHD hHD);
void hdEndFrame(HHD hHD);
HDErrorInfo hdGetError(void);
HDstring hdGetErrorString(HDerror errorCode);
void hdEnable(HDenum cap);
void hdDisable(HDenum cap);
void hdGetDoublev(HDenum pname, HDdouble* params);
void hdGetIntegerv(HDenum pname, HDint* params);
void hdSetDoublev(HDenum pname, const HDdouble* params);
void hdStartScheduler(void);
void hdStopScheduler(void);
void hdSetSchedulerRate(HDulong nRate);
HDSchedulerHandle hdScheduleAsynchronous(HDSchedulerCallback pCallback, void* pUserData, HDushort nPriority);
void hdUnschedule(HDSchedulerHandle hHandle);

#ifdef __cplusplus
}
#endif

#endif
