"""The programs ucsio writes for the robot to run, vendor-free: the generic
part of each (read the inputs, compute the poses, hand them to the vendor's
writer, write the files), which ``commands`` and ``demo`` both call.
``measure``: the measurement program (``program --measure``)."""
