# A forging chain in one file: hot upsetting (scene_hot.yaml), 5 s of transfer in air
# (scene_dwell.yaml: no dies, the temperature alone), a second blow by a new die (scene_hot_second.yaml).
# Each stage is a case that continues the one before (rksolve CASE --from PREVIOUS); the last one's
# vtk/chain.pvd shows the whole chain in ParaView, on one clock.
#   make chain                       (from the top folder: BUILD, RANKS as there)
#   make -f geometry/upsetting/chain.mk BIN=build/bin OUT=build/chain RANKS=2 SPACING=2.5e-3
BIN     ?= build/bin
OUT     ?= build/chain
RANKS   ?= 2
SPACING ?= 2.5e-3
HERE    := $(dir $(lastword $(MAKEFILE_LIST)))
PREP     = $(BIN)/rkprep $(1) --ranks $(RANKS) --out $(2) --force --quiet --set discretization.spacing=$(SPACING)
SOLVE    = mpirun -np $(RANKS) $(BIN)/rksolve

$(OUT)/second/vtk/chain.pvd: $(OUT)/transfer/solve.json
	$(call PREP,$(HERE)scene_hot_second.yaml,$(OUT)/second)
	$(SOLVE) $(OUT)/second --from $(OUT)/transfer
	$(BIN)/rkpost $(OUT)/second

$(OUT)/transfer/solve.json: $(OUT)/upset/solve.json
	$(call PREP,$(HERE)scene_dwell.yaml,$(OUT)/transfer)
	$(SOLVE) $(OUT)/transfer --from $(OUT)/upset
	$(BIN)/rkpost $(OUT)/transfer --no-pictures

$(OUT)/upset/solve.json:
	$(call PREP,$(HERE)scene_hot.yaml,$(OUT)/upset)
	$(SOLVE) $(OUT)/upset
	$(BIN)/rkpost $(OUT)/upset --no-pictures
