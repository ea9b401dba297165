# engine/metrics: image quality against a reference, on the CPU: PSNR, SSIM, FLIP, the Fourier-band
# error, flicker between frames and the change of an auto reference.
libaaengine_a_SOURCES += engine/metrics/metrics.h engine/metrics/metrics.c engine/metrics/ssim.c \
	engine/metrics/flip.h engine/metrics/flip.c engine/metrics/flip_internal.h engine/metrics/flip_color.c \
	engine/metrics/flip_simd.c engine/metrics/flip_pool.c engine/metrics/fourier.h engine/metrics/fourier.c \
	engine/metrics/flicker.c engine/metrics/change.c
