"""Read Exodus files with ParaView's own reader (pvbatch) and compare them point by point.

    pvbatch scripts/paraview_read.py JOINED.e SPREAD.e.N.0

Opening one file of a spread set makes ParaView load the whole set. Prints the number of
points and time steps of each, then exits 1 unless both hold the same global ids with the
same final displacement_x.
"""
import sys

from paraview import servermanager as sm
from paraview.simple import ExodusIIReader
from vtk.numpy_interface import dataset_adapter as dsa


def final_ux(path):
    reader = ExodusIIReader(FileName=[path])
    reader.PointVariables = ["displacement_"]
    times = list(reader.TimestepValues)
    reader.UpdatePipeline(times[-1])
    it = sm.Fetch(reader).NewIterator()
    it.InitTraversal()
    ux = {}
    while not it.IsDoneWithTraversal():
        block = dsa.WrapDataObject(it.GetCurrentDataObject())
        ux.update(zip(block.PointData["GlobalNodeId"], block.PointData["displacement_"][:, 0]))
        it.GoToNextItem()
    print("%s: %d points, %d time steps" % (path, len(ux), len(times)))
    return ux


a, b = (final_ux(p) for p in sys.argv[1:3])
if sorted(a) != sorted(b):
    sys.exit("the two files hold different points")
diff = max(abs(a[k] - b[k]) for k in a)
print("largest |displacement_x| difference: %g" % diff)
sys.exit(0 if diff == 0 else 1)
