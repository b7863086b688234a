"""Open Exodus files with ParaView's default reader, as File > Open or OpenDataFile does, and
count the points it loads (pvbatch).

    pvbatch scripts/paraview_points.py WANT FILE...

Prints the reader and the number of points of each file; exits 1 unless every file loads WANT
points. Relative names are opened as given, from the current folder (as a pvpython user types
them).
"""
import sys

from paraview.simple import Delete, OpenDataFile

want, files, fail = int(sys.argv[1]), sys.argv[2:], 0
for path in files:
    reader = OpenDataFile(path)
    reader.UpdatePipeline()
    n = reader.GetDataInformation().GetNumberOfPoints()
    ok = n == want
    fail |= not ok
    print("%s %s (%s): %d points of %d" % ("ok  " if ok else "FAIL", path, reader.GetXMLName(), n, want))
    Delete(reader)
sys.exit(fail)
