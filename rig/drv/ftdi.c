/*
 * ftdi.c - the FTDI USB-serial bridge inside APT controllers, driven
 * over raw USB as the Thorlabs protocol document prescribes
 * [APT Communications Protocol, §2.1 "USB interface": 115200 baud, 8 data
 * bits, 1 stop, no parity, RTS/CTS flow control, purge both buffers].
 * Every bulk IN packet (64 bytes at full speed) starts with two modem and
 * line status bytes, which are stripped here [FTDI AN232B-04 §4].
 */
#include <string.h>

#include "rig/devices.h"

#define FTDI_EP_OUT 0x02
#define FTDI_EP_IN 0x81
#define FTDI_PACKET 64
#define FTDI_STATUS_LEN 2
#define FTDI_REQ_OUT 0x40
#define FTDI_SIO_RESET 0
#define FTDI_SIO_MODEM_CTRL 1
#define FTDI_SIO_SET_FLOW_CTRL 2
#define FTDI_SIO_SET_BAUD_RATE 3
#define FTDI_SIO_SET_DATA 4
#define FTDI_SIO_SET_LATENCY_TIMER 9
#define FTDI_RESET_PURGE_RX 1
#define FTDI_RESET_PURGE_TX 2
#define FTDI_DIV_115200 0x001A	/* 3 MHz / 26, sub-integer bits 0 */
#define FTDI_DATA_8N1 0x0008
#define FTDI_FLOW_RTS_CTS 0x0100
#define FTDI_RTS_ON 0x0202	/* mask bit 9 (RTS), level bit 1 */
#define FTDI_LATENCY_MS 16	/* the chip's default, set explicitly */
#define FTDI_PURGE_DWELL_S 0.05	/* APT protocol §2.1: 50 ms each side */
#define FTDI_TIMEOUT_MS 500

/* The set-up of the APT protocol document, §2.1 (FT_SetBaudRate,
 * FT_SetDataCharacteristics, 50 ms, FT_Purge, 50 ms, FT_ResetDevice,
 * FT_SetFlowControl RTS/CTS, FT_SetRts), as FTDI vendor requests
 * [AN232B-04], plus the latency timer, so the timing does not depend on
 * what the EEPROM or the last program left.  On the FT232 of the APT
 * controllers wIndex of SET_BAUD_RATE carries divisor bit 16, not the
 * interface: interface + 1 there was the sub-integer code 0.375, 113744
 * baud (found by the umockdev test bed, rig/testbed/). */
int rig_ftdi_setup(struct rig_hal_dev *d, int interface)
{
	enum { PURGE_DWELL = 0xff };
	static const uint16_t steps[][2] = {
		{ FTDI_SIO_RESET, 0 },
		{ FTDI_SIO_SET_BAUD_RATE, FTDI_DIV_115200 },
		{ FTDI_SIO_SET_DATA, FTDI_DATA_8N1 },
		{ PURGE_DWELL, 0 },
		{ FTDI_SIO_RESET, FTDI_RESET_PURGE_RX },
		{ FTDI_SIO_RESET, FTDI_RESET_PURGE_TX },
		{ PURGE_DWELL, 0 },
		{ FTDI_SIO_SET_FLOW_CTRL, 0 },
		{ FTDI_SIO_MODEM_CTRL, FTDI_RTS_ON },
		{ FTDI_SIO_SET_LATENCY_TIMER, FTDI_LATENCY_MS },
	};
	uint16_t index = (uint16_t)(interface + 1);
	size_t i;
	int rc;

	for (i = 0; i < sizeof(steps) / sizeof(steps[0]); i++) {
		uint16_t ix = index;

		if (steps[i][0] == PURGE_DWELL) {
			rig_hal_sleep(d->hal, FTDI_PURGE_DWELL_S);
			continue;
		}
		if (steps[i][0] == FTDI_SIO_SET_FLOW_CTRL)
			ix |= FTDI_FLOW_RTS_CTS;
		if (steps[i][0] == FTDI_SIO_SET_BAUD_RATE)
			ix = (uint16_t)(FTDI_DIV_115200 >> 16);
		rc = rig_hal_usb_control(d, FTDI_REQ_OUT, (uint8_t)steps[i][0],
					 steps[i][1], ix, FTDI_TIMEOUT_MS);
		if (rc != RIG_OK)
			return rc;
	}
	return RIG_OK;
}

int rig_ftdi_read(struct rig_hal_dev *d, uint8_t *buf, size_t cap,
		  size_t *got, unsigned timeout_ms)
{
	uint8_t raw[8 * FTDI_PACKET];
	size_t n = 0, off, take;
	int rc;

	*got = 0;
	rc = rig_hal_usb_read(d, FTDI_EP_IN, raw, sizeof(raw), &n, timeout_ms);
	if (rc != RIG_OK)
		return rc;
	for (off = 0; off < n; off += FTDI_PACKET) {
		size_t pkt = n - off < FTDI_PACKET ? n - off : FTDI_PACKET;

		if (pkt <= FTDI_STATUS_LEN)
			continue;
		take = pkt - FTDI_STATUS_LEN;
		if (*got + take > cap)
			return RIG_EPROTO;
		memcpy(buf + *got, raw + off + FTDI_STATUS_LEN, take);
		*got += take;
	}
	return RIG_OK;
}

int rig_ftdi_write(struct rig_hal_dev *d, const uint8_t *buf, size_t len)
{
	return rig_hal_usb_write(d, FTDI_EP_OUT, buf, len, FTDI_TIMEOUT_MS);
}
