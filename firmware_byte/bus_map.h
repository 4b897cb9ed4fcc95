/*
 * bus_map.h — register map of the byte-side bus (rtl/byte_port.v), copied from
 * docs/byte-bus.md. Word addresses, 32-bit data.
 */
#ifndef BB_BUS_MAP_H
#define BB_BUS_MAP_H

#define BB_BUS_ID              0x00u  /* R  0xB17B7E01 */
#define BB_BUS_STATUS          0x01u  /* R  bit 0 NEXT, bit 1 running, bit 2 fault */
#define BB_BUS_DISPATCH_INSTR  0x02u  /* R  the dispatched instruction word */
#define BB_BUS_DISPATCH_CTX    0x03u  /* R  bit 0 RLO, bits 31..16 scan number */
#define BB_BUS_DISPATCH_MS     0x05u  /* R  TIME_MS in the dispatch's first clock */
#define BB_BUS_DISPATCH_IW     0x06u  /* R  the named IW in the dispatch's first clock */
#define BB_BUS_DONE            0x04u  /* W  bit 0 new RLO, bit 1 write the RLO */
#define BB_BUS_TIME_MS         0x08u  /* R  floor(clock / TICK_DIV) */
#define BB_BUS_TICK_DIV        0x09u  /* RW clocks per ms */
#define BB_BUS_CLOCK           0x0Au  /* R  clocks since clock 0, low 32 bits */
#define BB_BUS_TC_BIT          0x10u  /* W  bit 8 value, bit 6 counter, bits 5..0 n */
#define BB_BUS_T_STATUS_LO     0x11u
#define BB_BUS_T_STATUS_HI     0x12u
#define BB_BUS_C_STATUS_LO     0x13u
#define BB_BUS_C_STATUS_HI     0x14u
#define BB_BUS_T_ENABLE_LO     0x15u
#define BB_BUS_T_ENABLE_HI     0x16u
#define BB_BUS_C_PULSE_LO      0x17u
#define BB_BUS_C_PULSE_HI      0x18u
#define BB_BUS_FBY(k)          (0x20u + (unsigned)(k))  /* R  pop F_bB channel k, bit 0 */
#define BB_BUS_FBI(k)          (0x28u + (unsigned)(k))  /* W  push F_Bb channel k, bit 0 */
#define BB_BUS_CHAN_STATUS     0x30u
#define BB_BUS_IW(n)           (0x40u + (unsigned)(n))  /* R  input word n, sign-extended */
#define BB_BUS_QW(n)           (0x50u + (unsigned)(n))  /* RW output word n, low 16 bits */
#define BB_BUS_STALLS_BIT      0x60u
#define BB_BUS_STALLS_BYTE     0x61u
#define BB_BUS_BYTE_FLAGS      0x62u  /* RW sticky firmware flags (whole word written) */
/* Plant cores only (rtl/plc_core.v): word markers MW n, low 16 bits; a read takes 2
 * clocks (one "not ready" clock: the word RAM is synchronous). */
#define BB_BUS_MW(n)           (0x100u + (unsigned)(n))

#define BB_BUS_ID_VALUE        0xB17B7E01u

/* Field layout of DISPATCH_CTX, DONE and TC_BIT. */
#define BB_CTX_RLO             0x1u
#define BB_CTX_SCAN_SHIFT      16
#define BB_DONE_RLO            0x1u
#define BB_DONE_RLO_WE         0x2u
#define BB_TC_VALUE            (1u << 8)
#define BB_TC_COUNTER          (1u << 6)
#define BB_TC_INDEX_MASK       0x3Fu

/* Address windows (channel / word counts the bus can address). */
#define BB_BUS_CHANNELS        8u     /* 0x20..0x27, 0x28..0x2F */
#define BB_BUS_IW_WORDS        16u
#define BB_BUS_QW_WORDS        16u

#endif /* BB_BUS_MAP_H */
