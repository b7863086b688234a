#!/usr/bin/env bash
# A device is no output: /dev/null as output.file, a device node as restart.file (the checkpoint
# would be renamed over it) and as output.history_file are refused (exit 2, the key named, "is a
# character device"), nothing written, the device left a device. The checkpoint and history
# cases take device nodes made in the scratch folder (mknod, as root; else /dev/full for the
# history, and the checkpoint case is skipped): a broken build cannot replace /dev/null.
# usage: write_paths_device.sh PERIFEM SCRATCH   (from the tests/ folder)
source common/write_paths_env.sh
pd_deck "output: {file: /dev/null}" > exodus.yaml && refused exodus.yaml file "is a character device"
if mknod null c 1 3 2>/dev/null && mknod full c 1 7 2>/dev/null; then
  pd_deck "restart: {file: null, interval: 1}" > checkpoint.yaml && refused checkpoint.yaml file "is a character device"
  pd_deck "output: {history_file: full}" > history.yaml && refused history.yaml history_file "is a character device"
  [ -c null ] && [ -c full ] || { echo "FAIL: a device node was replaced"; fail=1; }
else
  echo "(not root: no device node of its own; the checkpoint case is not run)"
  pd_deck "output: {history_file: /dev/full}" > history.yaml && refused history.yaml history_file "is a character device"
fi
[ -c /dev/null ] || { echo "FAIL: /dev/null is no longer a device"; fail=1; }
exit $fail
