# engine/types: the data the layers above pass to each other: a job's spec and its results (job.h) and
# the contract every AA method fulfils (method.h). Headers only.
libaaengine_a_SOURCES += engine/types/job.h engine/types/method.h
